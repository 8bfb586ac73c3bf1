#pragma once
// The `candela` subcommands. Each returns the process exit code; errors go to stderr with the
// file and the problem, never a crash.

#include <string>
#include <vector>

namespace candela {

using Args = std::vector<std::string>;

int cmdRender(const Args& args);
int cmdProbe(const Args& args);
int cmdInfo(const Args& args);
int cmdEdit(const Args& args);
int cmdConvert(const Args& args);
int cmdBench(const Args& args);

/// Parses "WxH" (e.g. 512x512); throws InputError.
void parseSize(const std::string& text, int& width, int& height);
/// Value following a flag, or throws InputError naming the flag.
const std::string& flagValue(const Args& args, size_t& i);
int parseInt(const std::string& flag, const std::string& text, int min, int max);

}  // namespace candela
