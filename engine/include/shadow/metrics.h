// Error of an estimated visibility image against a truth image (e.g. a technique's
// visibility_<i>.exr against the ray-traced reference), and signed-error heat maps.
//
// The error of a pixel is e = estimate − truth: e < 0 means the estimate is too dark (false
// shadow, "acne"), e > 0 too light (light leaking). Statistics are taken over *receiver pixels*,
// the pixels a mask covers (mask > 0.5; normally position.exr's A, 1 on geometry), or every
// pixel when there is no mask. A receiver whose estimate is NaN or ±Inf is counted in
// `nonFinite` and scored as the worst estimate, |e| = 1 (towards the far end of [0, 1]: e = +1
// where V_true ≤ 0.5, −1 elsewhere), so a broken estimate can never score better than any real
// one and never turns a report into NaN. A receiver whose *truth* is not finite is bad input: an
// error naming the pixel.
//
// Truth classes (ε = kVisibilityClassEpsilon, which absorbs the reference's sampling noise and
// half-float round-off at the ends of [0, 1]):
//   lit       V_true ≥ 1 − ε
//   umbra     V_true ≤ ε
//   penumbra  ε < V_true < 1 − ε
//
// What this does not do: it does not align images (both must be rendered from the same camera
// at the same size), weigh pixels by screen area or radiance, or look at colour; it compares
// visibility only.
#pragma once

#include <shadow/image_io.h>
#include <shadow/result.h>
#include <shadow/shared_constants.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace shadow {

/// Width of the lit and umbra classes at the ends of [0, 1] (see the file comment).
inline constexpr double kVisibilityClassEpsilon = SG_VISIBILITY_CLASS_EPSILON;
/// |e| above which a pixel counts in `fractionOver0_1`.
inline constexpr double kLargeVisibilityError = 0.1;
/// A truly lit pixel whose estimate is below this is false shadow (acne); a truly umbral pixel
/// whose estimate is above it leaks light.
inline constexpr double kWrongSideVisibility = 0.5;
/// A truly umbral pixel whose estimate is above this shows light where there is none to see
/// (the faint-leak measure: visibility > 0.1 in the true umbra).
inline constexpr double kFaintLeakVisibility = 0.1;
/// An umbra pixel whose every neighbour within this many pixels (a square) is a receiver in the
/// true umbra too is *interior*: light there is a leak of the technique, not the map's texel
/// grid placing a shadow edge a fraction of a texel off.
inline constexpr int kInteriorUmbraMargin = 2;
/// Percentile reported as `p99`, by nearest rank.
inline constexpr int kErrorPercentile = 99;

/// Error statistics of one estimate against its truth. Every statistic is 0 when its
/// population is empty (the counts say so); none is ever NaN or Inf.
struct VisibilityErrors {
    // ---- Populations (pixels) ----
    std::int64_t receiverPixels = 0;       ///< pixels in the mask (every pixel without a mask)
    std::int64_t nonFinite = 0;            ///< receivers with a NaN/Inf estimate, scored |e| = 1
    std::int64_t validPixels = 0;          ///< receivers scored (all of them): population of rmse … p99
    std::int64_t litPixels = 0;            ///< valid, V_true ≥ 1 − ε
    std::int64_t penumbraPixels = 0;       ///< valid, ε < V_true < 1 − ε
    std::int64_t umbraPixels = 0;          ///< valid, V_true ≤ ε
    std::int64_t over0_1Pixels = 0;        ///< valid, |e| > kLargeVisibilityError
    std::int64_t acnePixels = 0;           ///< lit, estimate < kWrongSideVisibility
    std::int64_t leakPixels = 0;           ///< umbra, estimate > kWrongSideVisibility
    std::int64_t faintLeakPixels = 0;      ///< umbra, estimate > kFaintLeakVisibility
    std::int64_t interiorUmbraPixels = 0;  ///< umbra, kInteriorUmbraMargin from any other pixel
    std::int64_t interiorLeakPixels = 0;   ///< interior umbra, estimate > kFaintLeakVisibility

    // ---- Over valid pixels ----
    double rmse = 0.0;         ///< sqrt(mean e²)
    double mae = 0.0;          ///< mean |e|
    double meanError = 0.0;    ///< mean e (bias: < 0 too dark overall, > 0 too light)
    double maxAbsError = 0.0;  ///< max |e|
    /// Nearest-rank 99th percentile of |e|: the ⌈0.99·N⌉-th smallest of the N values
    /// (1-based), so at least 99% of the valid pixels have |e| ≤ p99. With N < 100 it is the
    /// maximum.
    double p99 = 0.0;
    double fractionOver0_1 = 0.0;  ///< over0_1Pixels / validPixels

    // ---- Per truth class ----
    double penumbraRmse = 0.0;  ///< sqrt(mean e²) over penumbra pixels
    double acneFraction = 0.0;  ///< acnePixels / litPixels
    /// Mean of max(0, V_true − estimate) over *all* lit pixels, so it also shows faint acne
    /// that never crosses kWrongSideVisibility.
    double acneMeanDarkening = 0.0;
    double leakFraction = 0.0;          ///< leakPixels / umbraPixels
    double faintLeakFraction = 0.0;     ///< faintLeakPixels / umbraPixels
    double interiorLeakFraction = 0.0;  ///< interiorLeakPixels / interiorUmbraPixels
    /// Mean of max(0, estimate − V_true) over all umbra pixels.
    double leakMeanLightening = 0.0;
};

/// Compares a one-channel `estimate` with a one-channel `truth` over the pixels where `mask`'s
/// last channel is > 0.5 (a non-finite mask value is not a receiver), or over every pixel when
/// `mask` is null. Errors: a size mismatch (naming both sizes), a channel count other than 1
/// (mask: any count ≥ 1), a receiver whose truth is not finite (naming the pixel `(x, y)`).
[[nodiscard]] Result<VisibilityErrors> compareVisibility(const ImageF& estimate, const ImageF& truth,
                                                         const ImageF* mask = nullptr);

/// The errors of several lights pooled, as one population of (light, pixel) pairs:
/// pixel-weighted, with p99 the percentile of the pooled |e| (not a mix of per-light
/// figures). `estimates[i]` is compared with `truths[i]`, all over the same `mask`. Errors: the
/// lists differ in length, or compareVisibility's errors for a light, prefixed "light <i>: ".
[[nodiscard]] Result<VisibilityErrors> compareVisibilityPooled(const std::vector<ImageF>& estimates,
                                                               const std::vector<ImageF>& truths,
                                                               const ImageF* mask = nullptr);

/// As above, with one mask per light: `masks[i]` selects the receivers of light i (e.g. the
/// reference's lit_<i>.exr: where the light shades the surface at all).
[[nodiscard]] Result<VisibilityErrors> compareVisibilityPooled(const std::vector<ImageF>& estimates,
                                                               const std::vector<ImageF>& truths,
                                                               const std::vector<ImageF>& masks);

/// Heat-map colour of a signed error, display-referred RGB in [0, 1]: white at 0, towards blue
/// (0,0,1) for e < 0 (estimate too dark), towards red (1,0,0) for e > 0 (too light); |e| ≥ 1
/// saturates. A non-finite `e` maps to kHeatMapBadColor.
[[nodiscard]] std::array<float, 3> errorColor(double e);

/// Colour of pixels outside the mask.
inline constexpr std::array<float, 3> kHeatMapBackground{0.5f, 0.5f, 0.5f};
/// Colour of receivers with a non-finite estimate or truth (not on the blue–white–red scale).
inline constexpr std::array<float, 3> kHeatMapBadColor{0.0f, 0.0f, 0.0f};

/// Signed-error heat map (3 channels, errorColor of every receiver, kHeatMapBackground
/// elsewhere), same size as the inputs. Same inputs and errors as compareVisibility.
[[nodiscard]] Result<ImageF> errorHeatMap(const ImageF& estimate, const ImageF& truth, const ImageF* mask = nullptr);

/// Writes a heat map (3 channels in [0, 1]) as an 8-bit RGB PNG, values as they are (they are
/// already display colours; no transfer curve).
[[nodiscard]] Status writeHeatMapPng(const std::string& path, const ImageF& heatMap);

/// One light of a folder comparison.
struct LightComparison {
    int index = 0;  ///< `<i>` of visibility_<i>.exr
    VisibilityErrors errors;
    ImageF heatMap;  ///< errorHeatMap of this light, for writeHeatMapPng
};

/// Two render folders compared light by light.
struct FolderComparison {
    int width = 0;
    int height = 0;
    /// Where the receiver mask came from: a position.exr path, the mask file given, or
    /// "none (every pixel)".
    std::string maskSource;
    std::vector<LightComparison> lights;  ///< in increasing `index`
    /// Every light's valid pixels pooled (pixel-weighted: a light with more receivers weighs
    /// more); counts are sums over the lights.
    VisibilityErrors allLights;
    /// Not errors, but worth telling: e.g. an estimate light the truth lacks (not compared).
    std::vector<std::string> warnings;
};

/// `compareFolders`' mask keyword: each light `<i>` judged over `truthDir`'s lit_<i>.exr (where the
/// reference says it shades the surface), as the error-against-time sweep judges it.
inline constexpr const char* kLitMasks = "lit";

/// Compares the visibility_<i>.exr of `truthDir` for every `<i>` in `lights` (every such file
/// found in `truthDir` when `lights` is empty) with the same file in `estimateDir`. The mask is
/// the EXR `maskPath` when not empty (its channel A, or Y when it has no A; `kLitMasks`: each
/// light's own lit_<i>.exr of `truthDir`), else truth's position.exr A, else the estimate's
/// position.exr A, else every pixel. Errors name
/// the file at fault: a missing or non-folder directory, a truth folder without visibility
/// files, a light missing from either folder, an unreadable EXR, a size mismatch, a non-finite
/// truth pixel.
[[nodiscard]] Result<FolderComparison> compareFolders(const std::string& estimateDir, const std::string& truthDir,
                                                      const std::string& maskPath = "",
                                                      const std::vector<int>& lights = {});

}  // namespace shadow
