// Visibility error metrics, signed-error heat maps, and the comparison of two render folders.
//
// One pass over the pixels feeds an ErrorAccumulator (sums and counts, plus every |e| for the
// percentile); a folder comparison merges the per-light accumulators into the pooled
// "all lights" one, so the aggregate is exactly the statistic of the pooled pixels (its p99
// included), not an average of per-light figures.
#include <shadow/metrics.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <regex>
#include <system_error>

namespace shadow {
namespace {

namespace fs = std::filesystem;

std::string sizeText(const ImageF& image) { return std::to_string(image.width) + "x" + std::to_string(image.height); }

bool sameSize(const ImageF& a, const ImageF& b) { return a.width == b.width && a.height == b.height; }

std::size_t pixelCount(const ImageF& image) {
    return static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
}

/// Pixel `i` is a receiver: covered by the mask's last channel, or any pixel without a mask.
bool isReceiver(const ImageF* mask, std::size_t i) {
    if (mask == nullptr) return true;
    const auto channels = static_cast<std::size_t>(mask->channels);
    return mask->pixels[i * channels + channels - 1] > 0.5f;  // NaN: false
}

/// A truth that is not finite at a receiver is no truth to score against: bad input.
Status checkTruthFinite(const ImageF& truth, const ImageF* mask) {
    for (int y = 0; y < truth.height; ++y) {
        for (int x = 0; x < truth.width; ++x) {
            const std::size_t i =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(truth.width) + static_cast<std::size_t>(x);
            if (isReceiver(mask, i) && !std::isfinite(truth.pixels[i])) {
                return Error{ErrorCode::InvalidValue, "truth pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                                          ") is not finite (" + std::to_string(truth.pixels[i]) + ")"};
            }
        }
    }
    return Ok{};
}

Status checkInputs(const ImageF& estimate, const ImageF& truth, const ImageF* mask) {
    if (estimate.channels != 1) {
        return Error{ErrorCode::MismatchedInputs,
                     "estimate has " + std::to_string(estimate.channels) + " channels, expected 1"};
    }
    if (truth.channels != 1) {
        return Error{ErrorCode::MismatchedInputs,
                     "truth has " + std::to_string(truth.channels) + " channels, expected 1"};
    }
    if (!sameSize(estimate, truth)) {
        return Error{ErrorCode::MismatchedInputs,
                     "size mismatch: estimate is " + sizeText(estimate) + ", truth is " + sizeText(truth)};
    }
    if (mask != nullptr) {
        if (mask->channels < 1) return Error{ErrorCode::MismatchedInputs, "mask has no channels"};
        if (!sameSize(*mask, truth)) {
            return Error{ErrorCode::MismatchedInputs,
                         "size mismatch: mask is " + sizeText(*mask) + ", truth is " + sizeText(truth)};
        }
    }
    // Buffers that disagree with their own header are a programming error, not input.
    assert(estimate.pixels.size() == pixelCount(estimate));
    assert(truth.pixels.size() == pixelCount(truth));
    assert(mask == nullptr || mask->pixels.size() == pixelCount(*mask) * mask->channels);
    return checkTruthFinite(truth, mask);
}

bool bothFinite(float estimate, float truth) { return std::isfinite(estimate) && std::isfinite(truth); }

/// Sums and counts of the errors of a set of pixels; `finish` turns them into statistics.
class ErrorAccumulator {
public:
    /// `interiorUmbra`: the pixel is interior umbra (see `kInteriorUmbraMargin`).
    /// `truth` is finite (checkTruthFinite).
    void addReceiver(float estimate, float truth, bool interiorUmbra) {
        ++counts_.receiverPixels;
        const double vTrue = truth;
        if (!std::isfinite(estimate)) {
            // The worst estimate: the far end of [0, 1] at |e| = 1.
            ++counts_.nonFinite;
            estimate = static_cast<float>(vTrue <= 0.5 ? vTrue + 1.0 : vTrue - 1.0);
        }
        const double e = static_cast<double>(estimate) - vTrue;
        const double absE = std::abs(e);
        ++counts_.validPixels;
        sum_ += e;
        sumAbs_ += absE;
        sumSq_ += e * e;
        maxAbs_ = std::max(maxAbs_, absE);
        absErrors_.push_back(static_cast<float>(absE));
        if (absE > kLargeVisibilityError) ++counts_.over0_1Pixels;

        if (vTrue >= 1.0 - kVisibilityClassEpsilon) {
            ++counts_.litPixels;
            darkening_ += std::max(0.0, -e);
            if (estimate < kWrongSideVisibility) ++counts_.acnePixels;
        } else if (vTrue <= kVisibilityClassEpsilon) {
            ++counts_.umbraPixels;
            lightening_ += std::max(0.0, e);
            if (estimate > kWrongSideVisibility) ++counts_.leakPixels;
            if (estimate > kFaintLeakVisibility) ++counts_.faintLeakPixels;
            if (interiorUmbra) {
                ++counts_.interiorUmbraPixels;
                if (estimate > kFaintLeakVisibility) ++counts_.interiorLeakPixels;
            }
        } else {
            ++counts_.penumbraPixels;
            penumbraSumSq_ += e * e;
        }
    }

    void merge(const ErrorAccumulator& other) {
        VisibilityErrors& c = counts_;
        const VisibilityErrors& o = other.counts_;
        c.receiverPixels += o.receiverPixels;
        c.nonFinite += o.nonFinite;
        c.validPixels += o.validPixels;
        c.litPixels += o.litPixels;
        c.penumbraPixels += o.penumbraPixels;
        c.umbraPixels += o.umbraPixels;
        c.over0_1Pixels += o.over0_1Pixels;
        c.acnePixels += o.acnePixels;
        c.leakPixels += o.leakPixels;
        c.faintLeakPixels += o.faintLeakPixels;
        c.interiorUmbraPixels += o.interiorUmbraPixels;
        c.interiorLeakPixels += o.interiorLeakPixels;
        sum_ += other.sum_;
        sumAbs_ += other.sumAbs_;
        sumSq_ += other.sumSq_;
        maxAbs_ = std::max(maxAbs_, other.maxAbs_);
        penumbraSumSq_ += other.penumbraSumSq_;
        darkening_ += other.darkening_;
        lightening_ += other.lightening_;
        absErrors_.insert(absErrors_.end(), other.absErrors_.begin(), other.absErrors_.end());
    }

    /// The statistics. Reorders the stored |e| values (for the percentile), nothing else.
    [[nodiscard]] VisibilityErrors finish() {
        VisibilityErrors r = counts_;
        r.rmse = std::sqrt(ratio(sumSq_, r.validPixels));
        r.mae = ratio(sumAbs_, r.validPixels);
        r.meanError = ratio(sum_, r.validPixels);
        r.maxAbsError = maxAbs_;
        r.p99 = nearestRankPercentile();
        r.fractionOver0_1 = ratio(static_cast<double>(r.over0_1Pixels), r.validPixels);
        r.penumbraRmse = std::sqrt(ratio(penumbraSumSq_, r.penumbraPixels));
        r.acneFraction = ratio(static_cast<double>(r.acnePixels), r.litPixels);
        r.acneMeanDarkening = ratio(darkening_, r.litPixels);
        r.leakFraction = ratio(static_cast<double>(r.leakPixels), r.umbraPixels);
        r.faintLeakFraction = ratio(static_cast<double>(r.faintLeakPixels), r.umbraPixels);
        r.interiorLeakFraction = ratio(static_cast<double>(r.interiorLeakPixels), r.interiorUmbraPixels);
        r.leakMeanLightening = ratio(lightening_, r.umbraPixels);
        return r;
    }

private:
    /// `sum / count`, 0 for an empty population.
    static double ratio(double sum, std::int64_t count) { return count > 0 ? sum / static_cast<double>(count) : 0.0; }

    /// The ⌈p·N/100⌉-th smallest |e| (1-based), in integers so that no rounding of p/100
    /// can move the rank.
    double nearestRankPercentile() {
        const std::size_t n = absErrors_.size();
        if (n == 0) return 0.0;
        const std::size_t p = kErrorPercentile;
        const std::size_t rank = (p * n + 99) / 100;  // ≥ 1 for n ≥ 1
        const auto nth = absErrors_.begin() + static_cast<std::ptrdiff_t>(rank - 1);
        std::nth_element(absErrors_.begin(), nth, absErrors_.end());
        return *nth;
    }

    VisibilityErrors counts_;  ///< only the counts are used until finish()
    double sum_ = 0.0;
    double sumAbs_ = 0.0;
    double sumSq_ = 0.0;
    double maxAbs_ = 0.0;
    double penumbraSumSq_ = 0.0;
    double darkening_ = 0.0;
    double lightening_ = 0.0;
    std::vector<float> absErrors_;
};

/// The accumulated receivers of validated inputs.
/// Whether pixel (x, y) and every pixel within kInteriorUmbraMargin of it (a square inside the
/// image) are receivers in the true umbra.
bool isInteriorUmbra(const ImageF& truth, const ImageF* mask, int x, int y) {
    const int m = kInteriorUmbraMargin;
    if (x < m || y < m || x + m >= truth.width || y + m >= truth.height) return false;
    for (int v = y - m; v <= y + m; ++v) {
        for (int u = x - m; u <= x + m; ++u) {
            const std::size_t j =
                static_cast<std::size_t>(v) * static_cast<std::size_t>(truth.width) + static_cast<std::size_t>(u);
            const float t = truth.pixels[j];
            if (!isReceiver(mask, j) || !std::isfinite(t) || t > kVisibilityClassEpsilon) return false;
        }
    }
    return true;
}

ErrorAccumulator accumulate(const ImageF& estimate, const ImageF& truth, const ImageF* mask) {
    ErrorAccumulator acc;
    for (int y = 0; y < truth.height; ++y) {
        for (int x = 0; x < truth.width; ++x) {
            const std::size_t i =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(truth.width) + static_cast<std::size_t>(x);
            if (!isReceiver(mask, i)) continue;
            acc.addReceiver(estimate.pixels[i], truth.pixels[i], isInteriorUmbra(truth, mask, x, y));
        }
    }
    return acc;
}

/// Heat map of validated inputs.
ImageF heatMapOf(const ImageF& estimate, const ImageF& truth, const ImageF* mask) {
    ImageF map = makeImage(truth.width, truth.height, 3);
    const std::size_t n = pixelCount(truth);
    for (std::size_t i = 0; i < n; ++i) {
        std::array<float, 3> rgb = kHeatMapBackground;
        if (isReceiver(mask, i)) {
            const float est = estimate.pixels[i];
            const float tru = truth.pixels[i];
            rgb = bothFinite(est, tru) ? errorColor(static_cast<double>(est) - tru) : kHeatMapBadColor;
        }
        std::copy(rgb.begin(), rgb.end(), map.pixels.begin() + static_cast<std::ptrdiff_t>(3 * i));
    }
    return map;
}

std::uint8_t toByte(float v) {
    if (!std::isfinite(v)) return 0;
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// ---- Folders --------------------------------------------------------------------------------

std::string joinPath(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

std::string visibilityName(int index) { return "visibility_" + std::to_string(index) + ".exr"; }

Status checkFolder(const std::string& dir, const std::string& role) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return Error{ErrorCode::FileUnreadable, dir + ": no such folder (" + role + ")"};
    if (!fs::is_directory(dir, ec)) return Error{ErrorCode::FileUnreadable, dir + ": not a folder (" + role + ")"};
    return Ok{};
}

/// The `<i>` of every visibility_<i>.exr in `dir`, increasing.
Result<std::vector<int>> visibilityIndices(const std::string& dir) {
    static const std::regex kName(R"(visibility_(\d{1,9})\.exr)");
    std::vector<int> indices;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        std::smatch m;
        if (std::regex_match(name, m, kName)) indices.push_back(std::stoi(m[1].str()));
    }
    if (ec) return Error{ErrorCode::FileUnreadable, dir + ": cannot list folder: " + ec.message()};
    std::sort(indices.begin(), indices.end());
    return indices;
}

bool isFile(const std::string& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

/// The receiver mask and where it came from.
struct Mask {
    std::optional<ImageF> image;
    std::string source;
};

/// A mask file given by the user: its channel A, or Y when it has no A.
Result<Mask> readMaskFile(const std::string& path) {
    if (!isFile(path)) return Error{ErrorCode::FileUnreadable, path + ": no such mask file"};
    Result<ImageF> alpha = readExr(path, {"A"});
    if (alpha.ok()) return Mask{std::move(alpha).value(), path};
    Result<ImageF> grey = readExr(path, {"Y"});
    if (grey.ok()) return Mask{std::move(grey).value(), path};
    return Error{alpha.error().code, alpha.error().message + " (a mask needs channel A or Y)"};
}

/// The mask of a folder comparison, in the order compareFolders documents.
Result<Mask> findMask(const std::string& maskPath, const std::string& truthDir, const std::string& estimateDir) {
    if (!maskPath.empty()) return readMaskFile(maskPath);
    for (const std::string& dir : {truthDir, estimateDir}) {
        const std::string position = joinPath(dir, "position.exr");
        if (!isFile(position)) continue;
        Result<ImageF> coverage = readExr(position, {"A"});
        if (!coverage.ok()) return coverage.error();
        return Mask{std::move(coverage).value(), position};
    }
    return Mask{std::nullopt, "none (every pixel)"};
}

/// Warnings for estimate lights the truth does not have.
std::vector<std::string> extraLightWarnings(const std::string& estimateDir, const std::vector<int>& estimateIndices,
                                            const std::vector<int>& truthIndices) {
    std::vector<std::string> warnings;
    for (int i : estimateIndices) {
        if (!std::binary_search(truthIndices.begin(), truthIndices.end(), i)) {
            warnings.push_back(joinPath(estimateDir, visibilityName(i)) +
                               ": the truth folder has no such light; not compared");
        }
    }
    return warnings;
}

/// Light `index`'s own mask: with `kLitMasks`, the truth's lit_<index>.exr (where the reference
/// says the light shades the surface); otherwise none (the folders' shared mask applies).
Result<Mask> ownMask(const std::string& maskPath, const std::string& truthDir, int index) {
    if (maskPath != kLitMasks) return Mask{std::nullopt, ""};
    return readMaskFile(joinPath(truthDir, "lit_" + std::to_string(index) + ".exr"));
}

}  // namespace

Result<VisibilityErrors> compareVisibility(const ImageF& estimate, const ImageF& truth, const ImageF* mask) {
    if (Status s = checkInputs(estimate, truth, mask); !s.ok()) return s.error();
    return accumulate(estimate, truth, mask).finish();
}

Result<VisibilityErrors> compareVisibilityPooled(const std::vector<ImageF>& estimates,
                                                 const std::vector<ImageF>& truths, const ImageF* mask) {
    if (estimates.size() != truths.size()) {
        return Error{ErrorCode::MismatchedInputs, std::to_string(estimates.size()) + " estimate images for " +
                                                      std::to_string(truths.size()) + " truth images"};
    }
    ErrorAccumulator pooled;
    for (std::size_t i = 0; i < truths.size(); ++i) {
        if (Status s = checkInputs(estimates[i], truths[i], mask); !s.ok()) {
            return s.error().within("light " + std::to_string(i) + ": ");
        }
        pooled.merge(accumulate(estimates[i], truths[i], mask));
    }
    return pooled.finish();
}

Result<VisibilityErrors> compareVisibilityPooled(const std::vector<ImageF>& estimates,
                                                 const std::vector<ImageF>& truths, const std::vector<ImageF>& masks) {
    if (estimates.size() != truths.size() || masks.size() != truths.size()) {
        return Error{ErrorCode::MismatchedInputs, std::to_string(estimates.size()) + " estimate images, " +
                                                      std::to_string(truths.size()) + " truth images and " +
                                                      std::to_string(masks.size()) + " masks"};
    }
    ErrorAccumulator pooled;
    for (std::size_t i = 0; i < truths.size(); ++i) {
        if (Status s = checkInputs(estimates[i], truths[i], &masks[i]); !s.ok()) {
            return s.error().within("light " + std::to_string(i) + ": ");
        }
        pooled.merge(accumulate(estimates[i], truths[i], &masks[i]));
    }
    return pooled.finish();
}

std::array<float, 3> errorColor(double e) {
    if (!std::isfinite(e)) return kHeatMapBadColor;
    const auto t = static_cast<float>(std::min(std::abs(e), 1.0));
    if (e < 0.0) return {1.0f - t, 1.0f - t, 1.0f};
    return {1.0f, 1.0f - t, 1.0f - t};
}

Result<ImageF> errorHeatMap(const ImageF& estimate, const ImageF& truth, const ImageF* mask) {
    if (Status s = checkInputs(estimate, truth, mask); !s.ok()) return s.error();
    return heatMapOf(estimate, truth, mask);
}

Status writeHeatMapPng(const std::string& path, const ImageF& heatMap) {
    if (heatMap.channels != 3) {
        return Error{ErrorCode::InvalidArgument,
                     path + ": heat map has " + std::to_string(heatMap.channels) + " channels, expected 3"};
    }
    std::vector<std::uint8_t> bytes(heatMap.pixels.size());
    std::transform(heatMap.pixels.begin(), heatMap.pixels.end(), bytes.begin(), toByte);
    return writePng(path, heatMap.width, heatMap.height, 3, bytes);
}

Result<FolderComparison> compareFolders(const std::string& estimateDir, const std::string& truthDir,
                                        const std::string& maskPath, const std::vector<int>& lights) {
    if (Status s = checkFolder(estimateDir, "estimate"); !s.ok()) return s.error();
    if (Status s = checkFolder(truthDir, "truth"); !s.ok()) return s.error();
    Result<std::vector<int>> truthIndices = visibilityIndices(truthDir);
    if (!truthIndices.ok()) return truthIndices.error();
    if (!lights.empty()) {
        truthIndices = lights;
        std::sort(truthIndices->begin(), truthIndices->end());
        truthIndices->erase(std::unique(truthIndices->begin(), truthIndices->end()), truthIndices->end());
    }
    if (truthIndices->empty())
        return Error{ErrorCode::FileUnreadable, truthDir + ": no visibility_<i>.exr files (truth)"};
    Result<std::vector<int>> estimateIndices = visibilityIndices(estimateDir);
    if (!estimateIndices.ok()) return estimateIndices.error();
    Result<Mask> mask = maskPath == kLitMasks ? Result<Mask>(Mask{std::nullopt, joinPath(truthDir, "lit_<i>.exr")})
                                              : findMask(maskPath, truthDir, estimateDir);
    if (!mask.ok()) return mask.error();
    const ImageF* maskImage = mask->image ? &*mask->image : nullptr;

    FolderComparison result;
    result.maskSource = mask->source;
    result.warnings = extraLightWarnings(estimateDir, *estimateIndices, *truthIndices);
    ErrorAccumulator pooled;
    for (int index : *truthIndices) {
        const std::string truthPath = joinPath(truthDir, visibilityName(index));
        const std::string estimatePath = joinPath(estimateDir, visibilityName(index));
        if (!isFile(truthPath))
            return Error{ErrorCode::FileUnreadable,
                         truthPath + ": missing (truth light " + std::to_string(index) + ")"};
        if (!isFile(estimatePath)) {
            return Error{ErrorCode::FileUnreadable, estimatePath + ": missing (the truth folder " + truthDir + " has " +
                                                        visibilityName(index) + ")"};
        }
        Result<ImageF> truth = readExr(truthPath, {"Y"});
        if (!truth.ok()) return truth.error();
        Result<ImageF> estimate = readExr(estimatePath, {"Y"});
        if (!estimate.ok()) return estimate.error();
        if (Status s = checkInputs(*estimate, *truth, maskImage); !s.ok()) {
            return s.error().within(estimatePath + " vs " + truthPath + " (mask " + mask->source + "): ");
        }
        if (result.lights.empty()) {
            result.width = truth->width;
            result.height = truth->height;
        } else if (truth->width != result.width || truth->height != result.height) {
            return Error{ErrorCode::MismatchedInputs,
                         truthPath + ": size " + sizeText(*truth) + " differs from the first light's " +
                             std::to_string(result.width) + "x" + std::to_string(result.height)};
        }
        Result<Mask> own = ownMask(maskPath, truthDir, index);
        if (!own.ok()) return own.error();
        const ImageF* lightMask = own->image ? &*own->image : maskImage;
        if (Status s = checkInputs(*estimate, *truth, lightMask); !s.ok()) {
            return s.error().within(estimatePath + " vs " + truthPath + " (mask " + own->source + "): ");
        }
        ErrorAccumulator light = accumulate(*estimate, *truth, lightMask);
        pooled.merge(light);
        result.lights.push_back({index, light.finish(), heatMapOf(*estimate, *truth, lightMask)});
    }
    result.allLights = pooled.finish();
    return result;
}

}  // namespace shadow
