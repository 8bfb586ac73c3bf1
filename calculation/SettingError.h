#pragma once
// A calculation's setting that cannot be used (a technique the luminaire's kind lacks, a grid
// spacing that is not a length): the error names the setting as the calculation knows it
// ("technique", "spacing"), and whoever took the setting from the user words it as they gave it:
// the command line as its option (app/main.cpp: "--technique: ..."), the editor as its field.

#include <string>

#include "util/Error.h"

namespace candela {

class SettingError : public InputError {
  public:
    /// what(): "SETTING: PROBLEM".
    SettingError(const std::string& setting, const std::string& problem)
        : InputError(setting + ": " + problem), setting_(setting), problem_(problem) {}
    const std::string& setting() const { return setting_; }
    const std::string& problem() const { return problem_; }

  private:
    std::string setting_, problem_;
};

}  // namespace candela
