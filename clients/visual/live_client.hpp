#pragma once
// visual-client --live (docs/visual.md, "Live"): the live loop, headless into numbered frames or
// in the window; the scene at rest when no hapticd answers.
#include "clients/visual/options.hpp"

namespace thx::visual {

int runLive(const Options& o);

}  // namespace thx::visual
