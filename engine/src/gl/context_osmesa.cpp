// Headless OpenGL through OSMesa (Mesa's llvmpipe here). The engine renders into its own
// framebuffer objects; the OSMesa buffer is a 1x1 placeholder needed only to make the context
// current.
#include <GL/osmesa.h>

#include <shadow/context_osmesa.h>

#include <array>
#include <memory>

namespace shadow {
namespace {

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(OSMesaContext ctx) : ctx_(ctx) {}
    ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    void makeCurrent() override { OSMesaMakeCurrent(ctx_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1); }
    [[nodiscard]] GlProcLoader loader() const override {
        return [](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); };
    }
    [[nodiscard]] const char* backend() const override { return "osmesa"; }

private:
    OSMesaContext ctx_;
    std::array<unsigned char, 4> pixel_{};
};

}  // namespace

Result<std::unique_ptr<GlContext>> createOsMesaContext() {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    OSMesaContext raw = OSMesaCreateContextAttribs(attribs, nullptr);
    if (raw == nullptr) return Error{ErrorCode::GlUnavailable, "OSMesa: could not create an OpenGL 4.5 core context"};
    auto ctx = std::make_unique<OsMesaContext>(raw);
    ctx->makeCurrent();
    if (Status s = loadGl(ctx->loader()); !s) return s.error();
    return std::unique_ptr<GlContext>(std::move(ctx));
}

}  // namespace shadow
