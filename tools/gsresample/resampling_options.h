// The resampler's parameters as command-line options (`--level 8`, ...), from the parameter
// table of resampling_params.h: for gsresample and gstile, which take the same options.
#ifndef GSRESAMPLE_RESAMPLING_OPTIONS_H
#define GSRESAMPLE_RESAMPLING_OPTIONS_H

#include <string>
#include <vector>

#include <vcg_ext/gaussphere/resampling_params.h>

namespace gsresample {

/// The table's entry whose option is `option` (e.g. "--level"), or null.
const vcg::gaussphere::ParameterSpec *FindOption(const std::string &option);

/// Parses `value` for `spec` into `param`, or explains why it cannot (strict_parse.h).
bool SetOption(const vcg::gaussphere::ParameterSpec &spec, const std::string &value,
               vcg::gaussphere::ResamplingParams &param, std::string &error);

/// Warnings for the options among `given` (as typed, e.g. "--level") that the other options
/// given override, so that they change nothing: the size controls (--max-error over --target
/// over --percentage; a target searches the level) and --exchanges, which only a target or
/// --spread-evenly uses.
std::vector<std::string> OverriddenOptions(const std::vector<std::string> &given,
                                           const vcg::gaussphere::ResamplingParams &param);

/// Two lines per option: `--level N (8; between 2 and 256)` and its help.
std::string OptionsUsage();

} // namespace gsresample

#endif
