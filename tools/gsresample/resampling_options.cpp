#include "resampling_options.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>

#include "strict_parse.h"

using namespace vcg::gaussphere;

namespace gsresample {

const ParameterSpec *FindOption(const std::string &option)
{
    for (const ParameterSpec &spec : ParameterTable())
        if (spec.option != nullptr && option == spec.option) return &spec;
    return nullptr;
}

bool SetOption(const ParameterSpec &spec, const std::string &value, ResamplingParams &param, std::string &error)
{
    const int intMax = std::numeric_limits<int>::max();
    double number = 0;
    if (spec.kind == ParameterKind::Bool) {
        int index = 0;
        if (!ParseChoice(value, {"0", "1"}, index, error)) return false;
        number = index;
    } else if (spec.kind == ParameterKind::Int) {
        int integer = 0;
        const int max = spec.max >= intMax ? intMax : int(spec.max);
        if (!ParseInt(value, int(spec.min), max, integer, error)) return false;
        number = integer;
    } else if (!ParseDouble(value, spec.min, spec.max, number, error)) {
        // In the table's words for the range, open bounds included ("above 1").
        const bool outOfRange = error.find("(out of range)") != std::string::npos;
        error = "expected a number " + spec.RangeText() + ", got " + Quoted(value) + (outOfRange ? " (out of range)" : "");
        return false;
    }
    if (!spec.Accepts(number)) {
        error = std::string(spec.kind == ParameterKind::Int ? "expected an integer " : "expected a number ") +
                spec.RangeText() + ", got " + Quoted(value) + " (out of range)";
        return false;
    }
    spec.set(param, number);
    return true;
}

std::string OptionsUsage()
{
    int width = 0; // the longest option name, so that the value columns line up
    for (const ParameterSpec &spec : ParameterTable())
        if (spec.option != nullptr) width = std::max(width, int(std::strlen(spec.option)));
    std::string text;
    for (const ParameterSpec &spec : ParameterTable()) {
        if (spec.option == nullptr) continue;
        char line[128];
        std::snprintf(line, sizeof line, "  %-*s %s (%g; %s)%s\n", width, spec.option,
                      spec.kind == ParameterKind::Int ? "N" : spec.kind == ParameterKind::Bool ? "0|1" : "X",
                      spec.defaultValue, spec.RangeText().c_str(),
                      spec.audience == ParameterAudience::Expert ? " [expert]" : "");
        text += line;
        text += "      " + std::string(spec.help) + "\n";
    }
    return text;
}

std::vector<std::string> OverriddenOptions(const std::vector<std::string> &given,
                                           const vcg::gaussphere::ResamplingParams &param)
{
    using vcg::gaussphere::SizeControl;
    const auto has = [&given](const char *option) { return std::find(given.begin(), given.end(), option) != given.end(); };
    const SizeControl mode = param.SizeMode();
    std::vector<std::string> warnings;
    const auto overridden = [&](const char *option, const char *by) {
        if (has(option)) warnings.push_back(std::string(option) + " has no effect: " + by + " sets the size");
    };
    if (mode == SizeControl::ErrorBound) {
        overridden("--target", "--max-error");
        overridden("--percentage", "--max-error");
    } else if (mode == SizeControl::TargetCount) {
        overridden("--level", "the target (the level is searched for)");
        if (param.targetCount > 0) overridden("--percentage", "--target");
    }
    if (has("--exchanges") && !(mode == SizeControl::TargetCount || param.spreadEvenly))
        warnings.push_back("--exchanges has no effect without --target, --percentage or --spread-evenly 1");
    return warnings;
}

} // namespace gsresample
