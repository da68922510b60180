// The tone map and the exposure meter's bins, written once for both sides: the CPU's
// (`toneMapToSrgb8`, `luminanceHistogram` in shadow/image_io.h: shadow_render's color.png) and the
// GPU's (`Renderer::presentToTexture` and `Renderer::meterExposure`: the viewer's window), so the
// two show the same pixels. C++ and GLSL both include this file: it holds preprocessor lines,
// comments, and functions of floats in the subset the two languages share (float literals with
// an f suffix, ?:, max, pow, log2; names prefixed sg_ as all of the module's GLSL).
//
// The curve: exposure, then Reinhard's x / (1 + x) on the colour's Rec. 709 luminance, the colour
// scaled with it so that its hue survives, scaled down as a whole when its brightest channel
// would pass 1 (rather than clipped per channel), then the sRGB encoding (IEC 61966-2-1).
#ifndef SG_TONE_MAP_H
#define SG_TONE_MAP_H

// The exposure meter counts pixels in SG_EXPOSURE_BINS bins of log2 luminance, evenly from
// 2^SG_EXPOSURE_LOG2_MIN to 2^SG_EXPOSURE_LOG2_MAX (1/8 of a stop each); a pixel darker than the
// first bin (the background, which is black, and black surfaces) is not counted, one brighter
// than the last counts in the last.
#define SG_EXPOSURE_BINS 384
#define SG_EXPOSURE_LOG2_MIN (-20.0f)
#define SG_EXPOSURE_LOG2_MAX 28.0f

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
namespace shadow::tone {
using std::exp2;
using std::log2;
using std::max;
using std::min;
using std::pow;
#define SG_TONE_FN inline
#else
#define SG_TONE_FN
#endif

/// Rec. 709 luminance of linear RGB.
SG_TONE_FN float sg_luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

/// Reinhard's curve (Reinhard et al. 2002), 0 at 0, 1 only at infinity: no highlight clips
/// (unlike the ACES fit, which reaches 1 at a finite value).
SG_TONE_FN float sg_toneCurve(float x) { return x / (1.0f + x); }

/// The factor every channel of an exposed colour (channels finite and >= 0) is multiplied by:
/// the curve over its luminance `lum`, or, where that would take its brightest channel
/// `brightest` past 1, the factor that brings that channel to 1.
SG_TONE_FN float sg_toneScale(float lum, float brightest) {
    float scale = lum > 0.0f ? sg_toneCurve(lum) / lum : 0.0f;
    return brightest * scale > 1.0f ? 1.0f / brightest : scale;
}

/// The sRGB opto-electronic transfer function, linear [0, 1] to encoded [0, 1].
SG_TONE_FN float sg_srgbEncode(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * pow(v, 1.0f / 2.4f) - 0.055f; }

/// Whether a pixel of luminance `lum` is counted by the exposure meter (it is not black).
SG_TONE_FN bool sg_exposureCounted(float lum) { return lum >= exp2(SG_EXPOSURE_LOG2_MIN); }

/// The exposure meter's bin of a counted luminance `lum`, 0 to SG_EXPOSURE_BINS - 1.
SG_TONE_FN int sg_exposureBin(float lum) {
    float t =
        (log2(lum) - SG_EXPOSURE_LOG2_MIN) * (float(SG_EXPOSURE_BINS) / (SG_EXPOSURE_LOG2_MAX - SG_EXPOSURE_LOG2_MIN));
    return int(min(max(t, 0.0f), float(SG_EXPOSURE_BINS - 1)));
}

#ifdef __cplusplus
}  // namespace shadow::tone
#endif
#undef SG_TONE_FN

#endif  // SG_TONE_MAP_H
