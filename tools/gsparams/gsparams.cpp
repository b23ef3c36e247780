// gsparams: what is made from the parameter table (vcg_ext/gaussphere/resampling_params.h)
// outside the code, so that it cannot drift from it; tests compare its output with the files.
//
//   gsparams readme       the README's parameter tables (markdown)
//   gsparams scripts DIR  the shipped .mlx scripts of the MeshLab filter, into DIR
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <vcg_ext/gaussphere/resampling_params.h>

using namespace vcg::gaussphere;

namespace {

/// A shipped script: its file name, what it is for, the values it sets apart from the defaults,
/// the filters that follow the resampling (empty: none) and which resampling filter it runs.
struct ShippedScript
{
    const char *file;
    const char *purpose;
    std::vector<std::pair<const char *, const char *>> values;
    const char *then = "";
    ResamplingFilter filter = ResamplingFilter::FeatureSensitive;
};

/// MeshLab 2020.09's Screened Poisson on the resampled layer (every parameter listed, as
/// meshlabserver needs), unweighted: the reconstruction filter's points are spread evenly, and
/// Screened Poisson gives every sample the same pull on the surface (docs/results.md,
/// "Reconstruction downstream").
const char *const kScreenedPoissonUnweighted =
    " <filter name=\"Surface Reconstruction: Screened Poisson\">\n"
    "  <Param type=\"RichBool\" value=\"false\" name=\"visibleLayer\"/>\n"
    "  <Param type=\"RichInt\" value=\"8\" name=\"depth\"/>\n"
    "  <Param type=\"RichInt\" value=\"5\" name=\"fullDepth\"/>\n"
    "  <Param type=\"RichInt\" value=\"0\" name=\"cgDepth\"/>\n"
    "  <Param type=\"RichFloat\" value=\"1.1\" name=\"scale\"/>\n"
    "  <Param type=\"RichFloat\" value=\"1.5\" name=\"samplesPerNode\"/>\n"
    "  <Param type=\"RichFloat\" value=\"4\" name=\"pointWeight\"/>\n"
    "  <Param type=\"RichInt\" value=\"8\" name=\"iters\"/>\n"
    "  <Param type=\"RichBool\" value=\"false\" name=\"confidence\"/>\n"
    "  <Param type=\"RichBool\" value=\"false\" name=\"preClean\"/>\n"
    " </filter>\n";

const std::vector<ShippedScript> &ShippedScripts()
{
    static const std::vector<ShippedScript> scripts = {
        {"resample_level8.mlx", "the defaults (level 8)", {}},
        {"resample_level16.mlx", "a finer Gaussian sphere: more surfels, lower error", {{"SubdivisionLevel", "16"}}},
        {"resample_level24.mlx", "finer still", {{"SubdivisionLevel", "24"}}},
        {"resample_10_percent.mlx", "exactly 10 % of the input points", {{"TargetPercentage", "10"}}},
        {"resample_max_error.mlx", "an error bound of 0.001 of the bounding-box diagonal", {{"MaxError", "0.001"}}},
        {"resample_colorize.mlx", "level 8, the input coloured by cluster", {{"ColorizeClusters", "true"}}},
        {"resample_level8_nofit.mlx", "level 8, surfels not fitted to the blended surface (FitOffsets off)", {{"FitOffsets", "false"}}},
        {"resample_and_reconstruct.mlx",
         "level 8's count spread evenly (*Gaussian Sphere Resampling for Surface Reconstruction*), then MeshLab's "
         "Screened Poisson (depth 8) on them",
         {}, kScreenedPoissonUnweighted, ResamplingFilter::ForReconstruction},
    };
    return scripts;
}

std::string Number(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

std::string DefaultText(const ParameterSpec &spec)
{
    if (spec.kind == ParameterKind::Bool) return spec.defaultValue != 0 ? "true" : "false";
    if (std::strcmp(spec.name, "WeightWidth") == 0) return "0 (1 % of the diagonal)";
    return Number(spec.defaultValue);
}

void PrintTable(ParameterAudience audience)
{
    std::printf("| name | `gsresample` | default | valid | meaning |\n|---|---|---|---|---|\n");
    for (const ParameterSpec &spec : ParameterTable()) {
        if (spec.audience != audience) continue;
        const std::string option = spec.option ? std::string("`") + spec.option + "`" : "(MeshLab only)";
        std::printf("| `%s` | %s | %s | %s | %s |\n", spec.name, option.c_str(), DefaultText(spec).c_str(),
                    spec.RangeText().c_str(), spec.help);
    }
}

void PrintReadme()
{
    PrintTable(ParameterAudience::Everyone);
    std::printf("\n*Gaussian Sphere Resampling for Surface Reconstruction* shows");
    const char *separator = " ";
    for (const ParameterSpec &spec : ParameterTable()) {
        if (!InDialog(spec, ResamplingFilter::ForReconstruction)) continue;
        std::printf("%s`%s`", separator, spec.name);
        separator = ", ";
    }
    std::printf(" (all of the above but `MaxError`) and always sets `SpreadEvenly`. For experts and for reproducing "
                "the paper, `gsresample` also takes (the MeshLab filters use the defaults):\n\n");
    PrintTable(ParameterAudience::Expert);
    std::printf("\nShipped scripts (`sample_data/`, made by `gsparams scripts`):\n\n| script | what |\n|---|---|\n");
    for (const ShippedScript &script : ShippedScripts()) std::printf("| `%s` | %s |\n", script.file, script.purpose);
}

/// The script's value of `spec`: its own, else the default, as MeshLab writes it.
std::string ScriptValue(const ShippedScript &script, const ParameterSpec &spec)
{
    for (const auto &value : script.values)
        if (std::strcmp(value.first, spec.name) == 0) return value.second;
    return spec.kind == ParameterKind::Bool ? DefaultText(spec) : Number(spec.defaultValue);
}

bool WriteScripts(const std::string &folder)
{
    for (const ShippedScript &script : ShippedScripts()) {
        for (const auto &value : script.values) {
            if (FindParameter(value.first) == nullptr) {
                std::fprintf(stderr, "gsparams: %s sets %s, which the table does not have\n", script.file, value.first);
                return false;
            }
        }
        const std::string path = folder + "/" + script.file;
        FILE *file = std::fopen(path.c_str(), "w");
        if (file == nullptr) {
            std::fprintf(stderr, "gsparams: cannot write %s\n", path.c_str());
            return false;
        }
        // MeshLab 2020.09's meshlabserver needs every parameter of the filter listed.
        std::fprintf(file, "<!DOCTYPE FilterScript>\n<FilterScript>\n <filter name=\"%s\">\n",
                     FilterTitle(script.filter));
        for (const ParameterSpec &spec : ParameterTable()) {
            if (!InDialog(spec, script.filter)) continue;
            const char *type = spec.kind == ParameterKind::Int ? "RichInt"
                             : spec.kind == ParameterKind::Float ? "RichFloat" : "RichBool";
            std::fprintf(file, "  <Param type=\"%s\" value=\"%s\" name=\"%s\"/>\n", type,
                         ScriptValue(script, spec).c_str(), spec.name);
        }
        std::fprintf(file, " </filter>\n%s</FilterScript>\n", script.then);
        if (std::fclose(file) != 0) return false;
    }
    return true;
}

} // namespace

int main(int argc, char **argv)
{
    if (argc == 2 && std::strcmp(argv[1], "readme") == 0) {
        PrintReadme();
        return 0;
    }
    if (argc == 3 && std::strcmp(argv[1], "scripts") == 0) return WriteScripts(argv[2]) ? 0 : 1;
    std::fprintf(stderr, "usage: gsparams readme | gsparams scripts DIR\n");
    return 2;
}
