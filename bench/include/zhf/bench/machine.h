// What a measured run records about where and when it ran.
#pragma once

#include <string>

namespace zhf::bench {

// /proc/cpuinfo's first "model name", or "unknown".
std::string cpu_model();

// Today's date in UTC, YYYY-MM-DD.
std::string today();

}  // namespace zhf::bench
