#include <shadow/components.h>

#include <array>
#include <string>
#include <string_view>

namespace shadow {

const char* lightTypeName(LightType t) {
    switch (t) {
        case LightType::Directional: return "directional";
        case LightType::Spot: return "spot";
        case LightType::Point: return "point";
    }
    return "point";
}

namespace {

/// One row of the technique table as the names need it.
struct TechniqueRow {
    ShadowTechnique technique;
    const char* name;
    const char* description;
    bool baseline;
};

constexpr std::array<TechniqueRow, kShadowTechniqueCount> kTechniques{{
#define SHADOW_TECHNIQUE_ROW(Enum, C, Name, I, G, Chain, Loops, Availability, Description) \
    {ShadowTechnique::Enum, Name, Description, std::string_view(#Availability) == "Baseline"},
    SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_ROW)
#undef SHADOW_TECHNIQUE_ROW
}};

const TechniqueRow& rowOf(ShadowTechnique t) {
    const auto i = static_cast<std::size_t>(t);
    return i < kTechniques.size() ? kTechniques[i] : kTechniques[0];
}

}  // namespace

const char* techniqueName(ShadowTechnique t) { return rowOf(t).name; }

const char* techniqueDescription(ShadowTechnique t) { return rowOf(t).description; }

bool techniqueAvailable(ShadowTechnique t) {
#ifdef SHADOW_BASELINE_TECHNIQUES
    return static_cast<std::size_t>(t) < kTechniques.size();
#else
    return static_cast<std::size_t>(t) < kTechniques.size() && !rowOf(t).baseline;
#endif
}

std::optional<ShadowTechnique> techniqueFromAnyName(std::string_view name) {
    for (const TechniqueRow& row : kTechniques) {
        if (name == row.name) return row.technique;
    }
    return std::nullopt;
}

std::optional<ShadowTechnique> techniqueFromName(std::string_view name) {
    const std::optional<ShadowTechnique> t = techniqueFromAnyName(name);
    return t && techniqueAvailable(*t) ? t : std::nullopt;
}

std::string techniqueNameList() {
    std::string list;
    for (const TechniqueRow& row : kTechniques) {
        if (techniqueAvailable(row.technique)) list += (list.empty() ? "" : ", ") + std::string(row.name);
    }
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

const char* depthModeName(DepthMode m) {
    switch (m) {
        case DepthMode::Nearest: return "nearest";
        case DepthMode::Midpoint: return "midpoint";
        case DepthMode::Second: return "second";
    }
    return "nearest";
}

std::optional<DepthMode> depthModeFromName(std::string_view name) {
    for (DepthMode m : {DepthMode::Nearest, DepthMode::Midpoint, DepthMode::Second}) {
        if (name == depthModeName(m)) return m;
    }
    return std::nullopt;
}

}  // namespace shadow
