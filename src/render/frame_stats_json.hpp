// FrameStats (the methods' typed per-frame statistics) as the JSON the CLI writes (--stats,
// --frame-stats, bench results): the keys starnt/frame_stats.hpp names beside each field.
#pragma once
#include <nlohmann/json.hpp>

#include "starnt/frame_stats.hpp"

namespace starnt {

nlohmann::json frameStatsJson(const FrameStats& stats);

}  // namespace starnt
