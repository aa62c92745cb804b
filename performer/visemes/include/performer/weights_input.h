// Reading a WeightTrack back from the CSV that write_weights_csv writes ("time,<channel>,..." then
// one row per frame), so weights can be computed once (`performer visemes`), edited or produced by
// another tool, and then drive a face (`performer face`, `performer pose`).
#pragma once

#include <filesystem>
#include <string_view>

#include "performer/viseme_set.h"
#include "performer/weights_track.h"

namespace performer {

// Channels are taken as named; the leading ones that name visemes of `set` count as the track's
// viseme channels. fps is 1 / the first frame interval (30 for a single frame). Times must
// increase; weights must be finite and in [0, 1]. Quoted fields (RFC 4180) are accepted in the
// header. Throws VisemeDataError "FILE:LINE: problem" for anything else: no header, a first
// column not called "time", repeated channel names, a row with the wrong field count, a
// non-numeric field, no rows.
WeightTrack parse_weights_csv(std::string_view text, std::string_view file_name, const VisemeSet& set);
WeightTrack read_weights_csv(const std::filesystem::path& file, const VisemeSet& set);

}  // namespace performer
