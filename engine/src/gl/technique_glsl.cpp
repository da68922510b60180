#include "gl/technique_glsl.h"

#include <shadow/shared_constants.h>

#include "gl/shader_sources.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace shadow::gpu {
namespace {

// The table's numbers are the GLSL constants' (every row checked).
#define SHADOW_TECHNIQUE_CHECK(Enum, Constant, ...) \
    static_assert(static_cast<int>(ShadowTechnique::Enum) == SG_TECH_##Constant, "SG_TECH_" #Constant);
SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_CHECK)
#undef SHADOW_TECHNIQUE_CHECK

/// What the GLSL writer needs of a row.
struct GlslRow {
    ShadowTechnique technique;
    std::string_view constant;  ///< CONSTANT: SG_TECH_<CONSTANT>
    std::string_view file;
    std::string_view glsl;
    int loops;
    bool baseline;
};

constexpr std::array<GlslRow, kShadowTechniqueCount> kRows{{
#define SHADOW_TECHNIQUE_GLSL_ROW(Enum, Constant, Name, File, Glsl, Chain, Loops, Availability, Description) \
    {ShadowTechnique::Enum, #Constant, File, #Glsl, Loops, std::string_view(#Availability) == "Baseline"},
    SHADOW_TECHNIQUE_TABLE(SHADOW_TECHNIQUE_GLSL_ROW)
#undef SHADOW_TECHNIQUE_GLSL_ROW
}};

constexpr const char* kLightVisibilitySignature = "float ";
constexpr const char* kLightVisibilityParameters =
    "(int slot, sg_GpuLight L, vec3 csPosition, vec3 wsNormal, vec3 geoNormal, float curvature,\n"
    "    float viewDistance)";

bool selected(unsigned techniques, const GlslRow& row) {
    return row.technique != ShadowTechnique::None && (techniques & techniqueBit(row.technique)) != 0;
}

std::string constantOf(const GlslRow& row) { return "SG_TECH_" + std::string(row.constant); }

/// The two functions of the dispatch over the rows selected; each line is wrapped in
/// `#ifdef SG_TECH_<CONSTANT>_ENABLED` when `conditional`.
std::string dispatch(unsigned techniques, bool conditional) {
    auto guarded = [conditional](const GlslRow& row, const std::string& line) {
        if (!conditional) return line;
        return "#ifdef " + constantOf(row) + "_ENABLED\n" + line + "#endif\n";
    };
    std::string policy =
        "// The receiver policy of technique `technique` (its share of bias and normal offset).\n"
        "sg_ReceiverPolicy sg_techniquePolicy(int technique) {\n"
        "    sg_ReceiverPolicy policy = sg_planePolicy();\n";
    std::string visibility =
        "// Visibility of light `L` (pass slot `slot`) at receiver `r` by the light's technique; 1\n"
        "// for a technique not compiled in.\n"
        "float sg_techniqueVisibility(int slot, sg_GpuLight L, sg_Receiver r) {\n"
        "    float v = 1.0;\n";
    std::string perTechnique =
        "// The visibility of a light whose technique is known when compiling (the engine's passes\n"
        "// name one per slot: SG_SLOT<i>_VISIBILITY), without the dispatch; parameters as\n"
        "// sg_shadowVisibility's.\n" +
        std::string(kLightVisibilitySignature) + "sg_unshadowedLightVisibility" + kLightVisibilityParameters +
        " {\n    return 1.0;\n}\n";
    for (const GlslRow& row : kRows) {
        if (!selected(techniques, row)) continue;
        const std::string glsl(row.glsl);
        policy += guarded(row, "    if (technique == " + constantOf(row) + ") policy = sg_" + glsl + "Policy();\n");
        visibility += guarded(row, "    SG_ISOLATED for (int k = 0; k < int(L.technique == " + constantOf(row) +
                                       "); ++k) v = sg_" + glsl + "Visibility(slot, L, r);\n");
        perTechnique += guarded(row, std::string(kLightVisibilitySignature) + "sg_" + glsl + "LightVisibility" +
                                         kLightVisibilityParameters + " {\n    SG_SHADOW_VISIBILITY_BODY(sg_" + glsl +
                                         "Policy(), sg_" + glsl + "Visibility)\n}\n");
    }
    policy += "    return policy;\n}\n\n";
    visibility += "    return v;\n}\n\n";
    return policy + visibility + perTechnique;
}

const char* const kHeader =
    "// The shadow techniques a program compiles and the dispatch on a light's technique, written\n"
    "// from the engine's technique table (engine/include/shadow/techniques.h).\n";

/// The `#include` lines of shaders/ files that `file` includes, in order.
std::vector<std::string> includesOf(std::string_view file) {
    std::vector<std::string> out;
    const char* text = findShaderSource(file);
    if (text == nullptr) return out;
    std::string_view rest(text);
    constexpr std::string_view kInclude = "#include \"";
    for (std::size_t at = rest.find(kInclude); at != std::string_view::npos; at = rest.find(kInclude, at + 1)) {
        const std::size_t begin = at + kInclude.size();
        const std::size_t end = rest.find('"', begin);
        if (end == std::string_view::npos) break;
        out.emplace_back(rest.substr(begin, end - begin));
    }
    return out;
}

/// Appends to `out`, after what it includes, every file `file` includes transitively (not
/// `file` itself), each once.
// NOLINTNEXTLINE(misc-no-recursion): as deep as the engine's own shader includes.
void collectIncludes(std::string_view file, std::vector<std::string>& out) {
    for (const std::string& child : includesOf(file)) {
        if (std::find(out.begin(), out.end(), child) != out.end()) continue;
        collectIncludes(child, out);
        if (std::find(out.begin(), out.end(), child) == out.end()) out.push_back(child);
    }
}

}  // namespace

void appendTechniqueDefines(unsigned techniques, std::vector<std::string>& defines) {
    for (const GlslRow& row : kRows) {
        if (selected(techniques, row)) defines.push_back(constantOf(row) + "_ENABLED");
    }
}

std::string techniquesGlsl(unsigned techniques) {
    std::string text = kHeader;
    text += "#include \"shadow_receiver.glsl\"\n";
    for (const GlslRow& row : kRows) {
        if (selected(techniques, row)) text += "#include \"" + std::string(row.file) + "\"\n";
    }
    return text + "\n" + dispatch(techniques, false);
}

std::string installedTechniquesGlsl() {
    unsigned publicTechniques = 0;
    std::vector<std::string> techniqueFiles;
    for (const GlslRow& row : kRows) {
        if (row.technique == ShadowTechnique::None || row.baseline) continue;
        publicTechniques |= techniqueBit(row.technique);
        techniqueFiles.emplace_back(row.file);
    }
    // What the receiver brings (shadow_visibility.glsl includes it first) need not be listed.
    std::vector<std::string> known;
    collectIncludes("shadow_receiver.glsl", known);
    known.emplace_back("shadow_receiver.glsl");
    std::vector<std::string> seen = known;
    for (const std::string& file : techniqueFiles) collectIncludes(file, seen);
    std::vector<std::string> shared{"shadow_receiver.glsl"};
    shared.insert(shared.end(), seen.begin() + static_cast<std::ptrdiff_t>(known.size()), seen.end());
    std::string text = kHeader;
    text +=
        "// A game's shader defines SG_TECH_<NAME>_ENABLED for the techniques it wants (one per\n"
        "// technique below) before it includes shadow.glsl; the files they share come first, so\n"
        "// that a loader that expands each file once finds them.\n"
        "#ifndef SG_SHADOW_TECHNIQUES\n#define SG_SHADOW_TECHNIQUES\n";
    for (const std::string& file : shared) {
        if (std::find(techniqueFiles.begin(), techniqueFiles.end(), file) == techniqueFiles.end()) {
            text += "#include \"" + file + "\"\n";
        }
    }
    for (const GlslRow& row : kRows) {
        if (!selected(publicTechniques, row)) continue;
        text += "#ifdef " + constantOf(row) + "_ENABLED\n#include \"" + std::string(row.file) + "\"\n#endif\n";
    }
    return text + "\n" + dispatch(publicTechniques, true) + "#endif\n";
}

std::string slotVisibilityFunction(ShadowTechnique t) {
    const auto i = static_cast<std::size_t>(t);
    if (t == ShadowTechnique::None || i >= kRows.size()) return "sg_unshadowedLightVisibility";
    return "sg_" + std::string(kRows[i].glsl) + "LightVisibility";
}

void appendSlotGroupDefines(std::span<const SlotConfig> slots, int capacity, std::vector<std::string>& defines) {
    int shadowed = 0;
    for (const SlotConfig& slot : slots) shadowed += slot.technique != SG_TECH_NONE ? 1 : 0;
    const bool groupAlike = shadowed > kMaxStraightLineSlots;
    std::vector<SlotConfig> configs;
    std::vector<std::vector<int>> members;
    for (std::size_t i = 0; i < slots.size(); ++i) {
        const auto found = groupAlike ? std::find(configs.begin(), configs.end(), slots[i]) : configs.end();
        if (found == configs.end()) {
            configs.push_back(slots[i]);
            members.push_back({static_cast<int>(i)});
        } else {
            members[static_cast<std::size_t>(found - configs.begin())].push_back(static_cast<int>(i));
        }
    }
    defines.push_back("SG_PASS_GROUPS " + std::to_string(configs.size()));
    // Loops in sequence: a light of its own runs its technique's loops, a point light's centre
    // tap may cross into another face (one more), a sun's cascade blend is one; a group of
    // several is one loop around them.
    int loops = 0;
    for (std::size_t g = 0; g < configs.size(); ++g) {
        const SlotConfig& c = configs[g];
        if (members[g].size() > 1) {
            ++loops;
        } else if (c.technique != SG_TECH_NONE) {
            loops += kRows[static_cast<std::size_t>(c.technique)].loops + (c.type == SG_LIGHT_POINT ? 1 : 0) +
                     (c.type == SG_LIGHT_DIRECTIONAL ? 1 : 0);
        }
    }
    if (loops > kMaxLoopsInSequence) defines.emplace_back("SG_ISOLATE_LOOPS");
    for (int g = 0; g < capacity; ++g) {
        const auto k = static_cast<std::size_t>(g);
        const SlotConfig c = k < configs.size() ? configs[k] : SlotConfig{};
        std::string list;
        for (int slot : k < members.size() ? members[k] : std::vector<int>{0}) {
            list += (list.empty() ? "" : ", ") + std::to_string(slot);
        }
        const std::string group = "SG_GROUP" + std::to_string(g);
        const std::size_t count = k < members.size() ? members[k].size() : 1;
        defines.push_back(group + "_COUNT " + std::to_string(count));
        defines.push_back(group + "_SLOTS int[](" + list + ")");
        defines.push_back(group + "_FIRST " + std::to_string(k < members.size() ? members[k].front() : 0));
        defines.push_back(group + "_TYPE " + std::to_string(c.type));
        defines.push_back(group + "_TECH " + std::to_string(c.technique));
        defines.push_back(group + "_KERNEL " + std::to_string(c.kernel));
        defines.push_back(group + "_VISIBILITY " + slotVisibilityFunction(static_cast<ShadowTechnique>(c.technique)));
    }
}

const char* techniqueGlslFile(ShadowTechnique t) {
    const auto i = static_cast<std::size_t>(t);
    return i < kRows.size() ? kRows[i].file.data() : "";
}

}  // namespace shadow::gpu
