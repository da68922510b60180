#include <shadow/components.h>

namespace shadow {

const char* lightTypeName(LightType t) {
    switch (t) {
        case LightType::Directional: return "directional";
        case LightType::Spot: return "spot";
        case LightType::Point: return "point";
    }
    return "point";
}

const char* techniqueName(ShadowTechnique t) {
    switch (t) {
        case ShadowTechnique::None: return "none";
        case ShadowTechnique::Hard: return "hard";
        case ShadowTechnique::Pcf: return "pcf";
        case ShadowTechnique::Pcss: return "pcss";
        case ShadowTechnique::PcssTextbook: return "pcss-textbook";
    }
    return "none";
}

std::optional<ShadowTechnique> techniqueFromName(std::string_view name) {
    for (ShadowTechnique t : {ShadowTechnique::None, ShadowTechnique::Hard, ShadowTechnique::Pcf, ShadowTechnique::Pcss,
                              ShadowTechnique::PcssTextbook}) {
        if (name == techniqueName(t)) return t;
    }
    return std::nullopt;
}

const char* filterKernelName(FilterKernel k) {
    switch (k) {
        case FilterKernel::Vogel: return "vogel";
        case FilterKernel::Poisson: return "poisson";
        case FilterKernel::Uniform: return "uniform";
    }
    return "vogel";
}

std::optional<FilterKernel> filterKernelFromName(std::string_view name) {
    for (FilterKernel k : {FilterKernel::Vogel, FilterKernel::Poisson, FilterKernel::Uniform}) {
        if (name == filterKernelName(k)) return k;
    }
    return std::nullopt;
}

}  // namespace shadow
