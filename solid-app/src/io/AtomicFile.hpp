// SPDX-License-Identifier: GPL-3.0-or-later
// Writes a whole file atomically: the content goes to "<path>.tmp.<pid>", then rename(2),
// so readers never see a half-written file. Throws std::runtime_error naming the path.
#pragma once
#include <string>

namespace fsi::io
{

void writeFileAtomically(const std::string& path, const std::string& content);

} // namespace fsi::io
