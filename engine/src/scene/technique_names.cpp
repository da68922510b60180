#include <shadow/components.h>

#include <array>
#include <string>

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
        case ShadowTechnique::Vsm: return "vsm";
        case ShadowTechnique::Vssm: return "vssm";
        case ShadowTechnique::Msm: return "msm";
        case ShadowTechnique::MsmSoft: return "msm-soft";
    }
    return "none";
}

namespace {

constexpr std::array kTechniques{ShadowTechnique::None, ShadowTechnique::Hard,         ShadowTechnique::Pcf,
                                 ShadowTechnique::Pcss, ShadowTechnique::PcssTextbook, ShadowTechnique::Vsm,
                                 ShadowTechnique::Vssm, ShadowTechnique::Msm,          ShadowTechnique::MsmSoft};

}  // namespace

std::optional<ShadowTechnique> techniqueFromName(std::string_view name) {
    for (ShadowTechnique t : kTechniques) {
        if (name == techniqueName(t)) return t;
    }
    return std::nullopt;
}

std::string techniqueNameList() {
    std::string list;
    for (ShadowTechnique t : kTechniques) list += (list.empty() ? "" : ", ") + std::string(techniqueName(t));
    return list;
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
