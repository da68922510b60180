// The summed-area table's number format (shadow_summed_area.comp.glsl builds it,
// shadow_summed_area.glsl reads it): moments of the scaled depth w in 24-bit fixed point, sums
// modulo 2^48 as two 24-bit limbs per moment, (w lo, w hi, w^2 lo, w^2 hi).
#ifndef SG_SHADOW_SUMMED_AREA_FORMAT
#define SG_SHADOW_SUMMED_AREA_FORMAT

// Units of the fixed point per scaled depth unit: one unit is 2^-24 / s of the layer's depth
// range, s its moment scale (the farthest caster at 1/4 to 1/2 of the fixed point's range), and
// the limb's mask.
const float sg_kSatUnit = 16777216.0;
const uint sg_kSatLimbMask = 0xFFFFFFu;

// a + b modulo 2^48, limb by limb with the carry: limbs of `a` below 2^24, of `b` at most 2^24.
uvec4 sg_satAdd(uvec4 a, uvec4 b) {
    uvec4 s = a + b;
    uvec2 carry = s.xz >> 24u;
    return uvec4(s.x & sg_kSatLimbMask, (s.y + carry.x) & sg_kSatLimbMask, s.z & sg_kSatLimbMask, (s.w + carry.y) & sg_kSatLimbMask);
}

#endif
