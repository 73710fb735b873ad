#pragma once
// A controller input (plan, schedule, run file) that cannot be used: the key-path error of every
// input file (common/key_path_error.hpp), "<file>: <key path>: <reason> (line <n>)", so that the
// user sees which file and which key to fix; the programs exit 1 on it.
#include "common/key_path_error.hpp"

namespace tongue::controller {

using InputError = common::KeyPathError;

}  // namespace tongue::controller
