#pragma once
// gnuplot as a child process whose image comes back through a pipe: the command then writes it
// through util/FileOutput.h (a temporary file and a rename, checked writes), which gnuplot's own
// `set output` could not give.

#include <string>

namespace candela {

/// Whether gnuplot is on the PATH.
bool gnuplotAvailable();

/// Runs gnuplot in `workingDir` (empty: the current folder) on `script`, given on its standard
/// input, and returns what it writes on its standard output (the image of a terminal with no
/// `set output`). Throws RuntimeError with gnuplot's messages when it fails or writes nothing;
/// `what` names the plot in that message.
std::string gnuplotOutput(const std::string& script, const std::string& workingDir,
                          const std::string& what);

}  // namespace candela
