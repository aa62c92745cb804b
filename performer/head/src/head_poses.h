// The procedural head's targets as poses: which movements make each viseme and expression.
// Private to the library.
#pragma once

#include <optional>
#include <string_view>

#include "head_pose.h"

namespace performer::detail {

// The pose for a viseme: by its thesis name (visemes.tsv) when it is one, else by its Oculus
// viseme; nullopt when neither is known.
std::optional<FacePose> viseme_pose(std::string_view name, std::string_view oculus);

// The pose for one of kHeadExpressions; nullopt for other names.
std::optional<FacePose> expression_pose(std::string_view name);

}  // namespace performer::detail
