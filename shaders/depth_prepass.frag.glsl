// Depth pre-pass: depth only, through the lit pass's own vertex shader (invariant position), so
// the lit pass can test EQUAL and shade each visible pixel once.
void main() {}
