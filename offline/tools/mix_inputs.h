// mix_inputs.h - the mixing options of the rendering tools (part of libdsn_tools.a): dsn-render and
// dsn-gpu-render read --mix, --weights, --weights-shift and --weights-periodic through these, load the
// other materials and the weight image the same way, and so render the same mix for the same options.
#ifndef DSN_TOOLS_MIX_INPUTS_H
#define DSN_TOOLS_MIX_INPUTS_H

#include <stdint.h>

#include <functional>
#include <string>
#include <vector>

#include "command_line.h"
#include "dsn/dsn.h"
#include "file_output.h"

namespace dsn {

// The usage lines of the four flags (for a tool's --help).
extern const char *const mix_usage;

struct MixOptions {
    std::vector<std::string> paths; // --mix: the materials after the tool's asset (material 0)
    std::string weights_path;       // --weights
    uint32_t weights_shift = 0;     // --weights-shift
    bool weights_periodic = false;  // --weights-periodic
};

// Reads the current flag into `options` when it is one of the four; false for any other flag.
bool parse_mix_flag(CommandLine &command_line, MixOptions &options);

// After parsing: UsageError for --mix without --weights or the reverse; the files to read, for
// check_outputs.
void check_mix_options(const MixOptions &options, std::vector<NamedPath> &inputs);

// What a mix keeps alive while it renders: the materials' asset bytes and noises, the weights.
struct MixInputs {
    std::vector<std::vector<unsigned char>> bytes;
    std::vector<dsn_asset> assets;
    std::vector<dsn_noise> noises;
    std::vector<uint8_t> weights;
    dsn_mix_control control{};
    dsn_mix mix;
};

// The mix of `noise` (material 0, configured with `config`) and the --mix assets configured with the
// same config, with the weight image: a grey image for two materials (black the first, white the second),
// else one channel per material. check_asset(path, asset) throws where the tool's mode cannot read an
// asset; `continuous` also checks each material as dsn_continuous_check does. Throws runtime_error with
// a one-line message on any failure.
void configure_mix(const MixOptions &options, const dsn_noise &noise, const dsn_config &config,
                   bool continuous,
                   const std::function<void(const std::string &, const dsn_asset &)> &check_asset,
                   MixInputs &inputs);

} // namespace dsn

#endif // DSN_TOOLS_MIX_INPUTS_H
