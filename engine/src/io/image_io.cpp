// PNG and OpenEXR writers, the EXR reader, tone mapping and atomic text files.
//
// Atomicity: every writer produces `<path>.tmp-<pid>` beside the target and renames it onto
// `path` only after the file is complete and closed. A failed or killed write therefore never
// leaves a partial file at `path`; a failed write also removes its temporary. The rename is
// atomic on POSIX file systems; there is no fsync, so this guards against a dying process, not
// against power loss.
//
// PNG encoding uses stb_image_write through Debian's libstb (pkg-config `stb`), which already
// contains the implementation; this file therefore does not define
// STB_IMAGE_WRITE_IMPLEMENTATION (a second copy would duplicate libstb's exported symbols).
// stb only reports "failed", so it encodes into memory and our own writer does the file I/O,
// where every error is checked and reported with its errno text.

#include <Imath/ImathBox.h>
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <shadow/image_io.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <set>
#include <system_error>

namespace shadow {
namespace {

/// Upper bound on the samples (pixels × channels) `readExr` allocates, so a corrupt or hostile
/// header cannot request an absurd allocation. 2^30 floats = 4 GiB, far above any render.
constexpr std::int64_t kMaxExrSamples = std::int64_t{1} << 30;

/// Half-float limit: larger finite values are clamped so a bright pixel never becomes Inf.
constexpr float kHalfMax = 65504.0f;

/// `"<path>: <cause>"`, with the code of what went wrong.
Error pathError(const std::string& path, ErrorCode code, const std::string& cause) {
    return Error{code, path + ": " + cause};
}

/// Thread-safe errno text (std::strerror is not).
std::string errnoText(int err) { return std::generic_category().message(err); }

/// The temporary beside `path`: same directory, so the final rename never crosses devices.
std::string tempPathFor(const std::string& path) {
    return path + ".tmp-" + std::to_string(static_cast<long>(::getpid()));
}

void removeQuietly(const std::string& file) {
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
}

/// Runs `write(tempPath)` and renames the result onto `path`. `write` returns a Status whose
/// error message is the bare cause; this adds the target path. The temporary is removed on
/// every failure.
template <typename WriteFn>
Status writeViaTemp(const std::string& path, WriteFn&& write) {
    if (path.empty()) return Error{ErrorCode::InvalidArgument, "empty output path"};
    const std::string temp = tempPathFor(path);
    Status written = write(temp);
    if (!written.ok()) {
        removeQuietly(temp);
        return written.error().within(path + ": ");
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        removeQuietly(temp);
        return pathError(path, ErrorCode::FileUnwritable, "cannot rename temporary file into place: " + ec.message());
    }
    return Ok{};
}

/// Writes `size` bytes to `file` (created or truncated), checking open, write and close.
Status writeBytes(const std::string& file, const void* data, std::size_t size) {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (f == nullptr) return Error{ErrorCode::FileUnwritable, "cannot open for writing: " + errnoText(errno)};
    const bool wrote = std::fwrite(data, 1, size, f) == size;
    const int writeErr = errno;
    const bool closed = std::fclose(f) == 0;  // flushes: a full disk may show up only here
    if (!wrote) return Error{ErrorCode::FileUnwritable, "write failed: " + errnoText(writeErr)};
    if (!closed) return Error{ErrorCode::FileUnwritable, "write failed on close: " + errnoText(errno)};
    return Ok{};
}

/// Runs `f`, turning any exception (OpenEXR reports every failure by throwing) into an Error.
template <typename T, typename F>
Result<T> catchAll(F&& f) {
    try {
        return f();
    } catch (const std::exception& e) {
        return Error{ErrorCode::MalformedFile, e.what()};
    } catch (...) {
        return Error{ErrorCode::Internal, "unknown error"};
    }
}

// ---- PNG ------------------------------------------------------------------------------------

Status validatePngArgs(int width, int height, int channels, std::size_t bytes) {
    if (width <= 0 || height <= 0) {
        return Error{ErrorCode::InvalidArgument, "bad size " + std::to_string(width) + "x" + std::to_string(height)};
    }
    if (channels != 3 && channels != 4) {
        return Error{ErrorCode::InvalidArgument, "PNG needs 3 or 4 channels, got " + std::to_string(channels)};
    }
    if (static_cast<std::int64_t>(width) * channels > INT_MAX) return Error{ErrorCode::InvalidArgument, "row too wide"};
    const std::size_t expected = static_cast<std::size_t>(width) * height * channels;
    if (bytes != expected) {
        return Error{ErrorCode::InvalidArgument,
                     "pixel buffer holds " + std::to_string(bytes) + " bytes, expected " + std::to_string(expected)};
    }
    return Ok{};
}

void appendToVector(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

/// PNG file bytes for validated arguments; empty if stb fails (it can only run out of memory).
std::vector<std::uint8_t> encodePng(int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
    std::vector<std::uint8_t> png;
    const int ok =
        stbi_write_png_to_func(appendToVector, &png, width, height, channels, pixels.data(), width * channels);
    if (ok == 0) png.clear();
    return png;
}

// ---- EXR ------------------------------------------------------------------------------------

Status validateExrArgs(const ImageF& image, const std::vector<std::string>& names) {
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0) {
        return Error{ErrorCode::InvalidArgument, "bad image size " + std::to_string(image.width) + "x" +
                                                     std::to_string(image.height) + "x" +
                                                     std::to_string(image.channels)};
    }
    const std::size_t expected = static_cast<std::size_t>(image.width) * image.height * image.channels;
    if (image.pixels.size() != expected) {
        return Error{ErrorCode::InvalidArgument, "pixel buffer holds " + std::to_string(image.pixels.size()) +
                                                     " floats, expected " + std::to_string(expected)};
    }
    if (names.size() != static_cast<std::size_t>(image.channels)) {
        return Error{ErrorCode::InvalidArgument, std::to_string(names.size()) + " channel names for " +
                                                     std::to_string(image.channels) + " channels"};
    }
    std::set<std::string> seen;
    for (const std::string& name : names) {
        if (name.empty()) return Error{ErrorCode::InvalidArgument, "empty channel name"};
        if (!seen.insert(name).second)
            return Error{ErrorCode::InvalidArgument, "duplicate channel name '" + name + "'"};
    }
    return Ok{};
}

/// `pixels` as half floats; finite values beyond the half range clamp to ±65504.
std::vector<half> toHalf(const std::vector<float>& pixels) {
    std::vector<half> out(pixels.size());
    std::transform(pixels.begin(), pixels.end(), out.begin(),
                   [](float v) { return half(std::isfinite(v) ? std::clamp(v, -kHalfMax, kHalfMax) : v); });
    return out;
}

/// A frame buffer over an interleaved buffer of `image.channels` samples per pixel, one slice
/// per name. `base` is the first sample of the buffer (float or half, as `type` says).
Imf::FrameBuffer interleavedFrameBuffer(const char* base, std::size_t sampleSize, Imf::PixelType type,
                                        const Imath::Box2i& window, int channels,
                                        const std::vector<std::string>& names) {
    const std::size_t xStride = sampleSize * static_cast<std::size_t>(channels);
    const std::size_t yStride = xStride * static_cast<std::size_t>(window.size().x + 1);
    Imf::FrameBuffer fb;
    for (std::size_t c = 0; c < names.size(); ++c) {
        fb.insert(names[c], Imf::Slice::Make(type, base + c * sampleSize, window, xStride, yStride));
    }
    return fb;
}

/// Writes a scanline, ZIP-compressed EXR of `image` (validated) to `file`.
Status writeExrFile(const std::string& file, const ImageF& image, const std::vector<std::string>& names,
                    ExrPixelType type) {
    const Imf::PixelType exrType = type == ExrPixelType::Half ? Imf::HALF : Imf::FLOAT;
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;  // lossless; good on smooth float data
    for (const std::string& name : names) header.channels().insert(name, Imf::Channel(exrType));

    std::vector<half> halves;
    const char* base = reinterpret_cast<const char*>(image.pixels.data());
    std::size_t sampleSize = sizeof(float);
    if (type == ExrPixelType::Half) {
        halves = toHalf(image.pixels);
        base = reinterpret_cast<const char*>(halves.data());
        sampleSize = sizeof(half);
    }
    const Imath::Box2i window = header.dataWindow();
    // The OutputFile is closed (destroyed) before the caller renames the file.
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(interleavedFrameBuffer(base, sampleSize, exrType, window, image.channels, names));
    out.writePixels(image.height);
    return Ok{};
}

/// The channel names a file holds, for error messages.
std::string channelList(const Imf::ChannelList& channels) {
    std::string list;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        list += (list.empty() ? "" : ", ") + std::string(it.name());
    }
    return list;
}

/// Checks that every requested name is present once in `channels`; the error names the first
/// missing or repeated one.
Status checkRequestedChannels(const Imf::ChannelList& channels, const std::vector<std::string>& names) {
    if (names.empty()) return Error{ErrorCode::InvalidArgument, "no channels requested"};
    std::set<std::string> seen;
    for (const std::string& name : names) {
        if (!seen.insert(name).second)
            return Error{ErrorCode::InvalidArgument, "channel '" + name + "' requested twice"};
        if (channels.findChannel(name) == nullptr) {
            return Error{ErrorCode::MalformedFile,
                         "no channel '" + name + "' (file has " + channelList(channels) + ")"};
        }
    }
    return Ok{};
}

/// Image dimensions of the data window, or an error if they are empty or absurd.
Result<ImageF> allocateFor(const Imath::Box2i& window, std::size_t channels) {
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
    if (width <= 0 || height <= 0) return Error{ErrorCode::MalformedFile, "empty data window"};
    if (width > kMaxExrSamples / height / static_cast<std::int64_t>(channels)) {
        return Error{ErrorCode::LimitExceeded,
                     "data window " + std::to_string(width) + "x" + std::to_string(height) + " is too large"};
    }
    return makeImage(static_cast<int>(width), static_cast<int>(height), static_cast<int>(channels));
}

Result<ImageF> readExrFile(const std::string& path, const std::vector<std::string>& names) {
    Imf::InputFile in(path.c_str());
    const Status requested = checkRequestedChannels(in.header().channels(), names);
    if (!requested.ok()) return requested.error();
    const Imath::Box2i window = in.header().dataWindow();
    Result<ImageF> image = allocateFor(window, names.size());
    if (!image.ok()) return image;
    // The data window's top row (min.y) lands in row 0: EXR's y grows downwards, as ours does.
    in.setFrameBuffer(interleavedFrameBuffer(reinterpret_cast<const char*>(image->pixels.data()), sizeof(float),
                                             Imf::FLOAT, window, image->channels, names));
    in.readPixels(window.min.y, window.max.y);
    return image;
}

// ---- Tone mapping ---------------------------------------------------------------------------

/// [0,1] to 0..255, rounding to nearest; out-of-range values clamp.
std::uint8_t toUnorm8(float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

float luminance(const float* rgb) { return tone::sg_luminance(rgb[0], rgb[1], rgb[2]); }

/// Tone maps one linear RGB pixel into `out` (shadow/tone_map.h), after making its channels what
/// the shared functions take: finite and >= 0 (negative, NaN and -inf black; +inf, or a colour
/// "very bright": its infinite channels 1, the others 0; a colour whose luminance overflows, its
/// brightest channel 1).
void toneMapPixel(const float* rgb, float exposure, std::uint8_t* out) {
    float c[3];
    for (int k = 0; k < 3; ++k) {
        const float v = std::isfinite(rgb[k]) ? rgb[k] * exposure : 0.0f;
        c[k] = v > 0.0f ? v : 0.0f;  // negative, NaN (from a NaN exposure) and -inf are black
    }
    float scale = 1.0f;
    if (std::isinf(c[0]) || std::isinf(c[1]) || std::isinf(c[2])) {
        for (float& channel : c) channel = std::isinf(channel) ? 1.0f : 0.0f;
    } else {
        const float lum = luminance(c);
        const float brightest = std::max({c[0], c[1], c[2]});
        scale = std::isinf(lum) ? 1.0f / brightest : tone::sg_toneScale(lum, brightest);
    }
    for (int k = 0; k < 3; ++k) out[k] = toUnorm8(tone::sg_srgbEncode(c[k] * scale));
}

/// Alpha is coverage, not light: stored linearly, clamped, no exposure or curve.
std::uint8_t alphaTo8(float a) { return std::isfinite(a) ? toUnorm8(a) : 0; }

}  // namespace

ImageF makeImage(int width, int height, int channels) {
    assert(width >= 0 && height >= 0 && channels >= 0);
    ImageF image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels.assign(static_cast<std::size_t>(width) * height * channels, 0.0f);
    return image;
}

Status writePng(const std::string& path, int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
    const Status valid = validatePngArgs(width, height, channels, pixels.size());
    if (!valid.ok()) return valid.error().within(path + ": ");
    const std::vector<std::uint8_t> png = encodePng(width, height, channels, pixels);
    if (png.empty()) return pathError(path, ErrorCode::Internal, "PNG encoding failed");
    return writeViaTemp(path, [&png](const std::string& temp) { return writeBytes(temp, png.data(), png.size()); });
}

Status writeExr(const std::string& path, const ImageF& image, const std::vector<std::string>& names,
                ExrPixelType type) {
    const Status valid = validateExrArgs(image, names);
    if (!valid.ok()) return valid.error().within(path + ": ");
    return writeViaTemp(path, [&](const std::string& temp) {
        return catchAll<Ok>([&] { return writeExrFile(temp, image, names, type); });
    });
}

Result<ImageF> readExr(const std::string& path, const std::vector<std::string>& names) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        return Error{ErrorCode::FileUnreadable, path + ": no such file (or not a regular file)"};
    }
    Result<ImageF> image = catchAll<ImageF>([&] { return readExrFile(path, names); });
    if (!image.ok()) return image.error().within(path + ": ");
    return image;
}

std::vector<std::uint8_t> toneMapToSrgb8(const ImageF& rgb, float exposure) {
    assert(rgb.channels == 3 || rgb.channels == 4);
    assert(rgb.pixels.size() == static_cast<std::size_t>(rgb.width) * rgb.height * rgb.channels);
    if (rgb.channels != 3 && rgb.channels != 4) return {};
    std::vector<std::uint8_t> out(rgb.pixels.size());
    const std::size_t channels = static_cast<std::size_t>(rgb.channels);
    for (std::size_t i = 0; i < rgb.pixels.size(); i += channels) {
        toneMapPixel(&rgb.pixels[i], exposure, &out[i]);
        if (channels == 4) out[i + 3] = alphaTo8(rgb.pixels[i + 3]);
    }
    return out;
}

LuminanceHistogram luminanceHistogram(const ImageF& rgb) {
    LuminanceHistogram counts{};
    if (rgb.channels < 3) return counts;
    for (std::size_t i = 0; i + 2 < rgb.pixels.size(); i += static_cast<std::size_t>(rgb.channels)) {
        const float* p = &rgb.pixels[i];
        if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) continue;
        const float lum = luminance(p);
        if (tone::sg_exposureCounted(lum)) ++counts[static_cast<std::size_t>(tone::sg_exposureBin(lum))];
    }
    return counts;
}

namespace {

/// log2 of the luminance at the centre of exposure-meter bin `bin`.
double binLog2(std::size_t bin) {
    constexpr double kStep = (SG_EXPOSURE_LOG2_MAX - SG_EXPOSURE_LOG2_MIN) / SG_EXPOSURE_BINS;
    return SG_EXPOSURE_LOG2_MIN + (static_cast<double>(bin) + 0.5) * kStep;
}

}  // namespace

float exposureFromHistogram(const LuminanceHistogram& histogram, const ExposureSettings& settings) {
    const auto clampOr = [](float v, float lo, float hi, float fallback) {
        return std::isfinite(v) ? std::clamp(v, lo, hi) : fallback;
    };
    const ExposureSettings d;
    const double key = clampOr(settings.key, 1e-6f, 1e3f, d.key);
    const double percentile = clampOr(settings.highlightPercentile, 1e-6f, 1.0f, d.highlightPercentile);
    const double stops = clampOr(settings.highlightStops, 0.0f, 30.0f, d.highlightStops);
    double total = 0.0, logSum = 0.0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        total += histogram[b];
        logSum += histogram[b] * binLog2(b);
    }
    if (total == 0.0) return 1.0f;
    // The highlight: the first bin at which the pixels counted reach the percentile.
    double below = 0.0, highlight = binLog2(histogram.size() - 1);
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        below += histogram[b];
        if (below >= percentile * total) {
            highlight = binLog2(b);
            break;
        }
    }
    const double metered = std::max(logSum / total, highlight - stops);
    const double exposure = key / std::exp2(metered);
    return std::isfinite(exposure) ? static_cast<float>(std::clamp(exposure, 1e-8, 1e8)) : 1.0f;
}

float autoExposure(const ImageF& rgb, float key) {
    return exposureFromHistogram(luminanceHistogram(rgb), {.key = key});
}

Status writeTextFileAtomic(const std::string& path, const std::string& text) {
    return writeViaTemp(path, [&text](const std::string& temp) { return writeBytes(temp, text.data(), text.size()); });
}

std::optional<std::string> notRegularFile(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    switch (st.type()) {
        case std::filesystem::file_type::regular: return std::nullopt;
        case std::filesystem::file_type::not_found: return std::string("no such file");
        case std::filesystem::file_type::directory: return std::string("not a regular file (a directory)");
        case std::filesystem::file_type::fifo: return std::string("not a regular file (a FIFO)");
        case std::filesystem::file_type::socket: return std::string("not a regular file (a socket)");
        case std::filesystem::file_type::block:
        case std::filesystem::file_type::character: return std::string("not a regular file (a device)");
        default: break;
    }
    return ec ? "cannot be read (" + ec.message() + ")" : std::string("not a regular file");
}

}  // namespace shadow
