#pragma once
// Names for what the view window saves (S, the panel's PNG / EXR / preset buttons): numbered, so a
// second save never overwrites the first.
#include <filesystem>
#include <string>

namespace tallow::app {

/// `base`-NNNN`extension` (e.g. "shots/tallow-blob-0003.png"), NNNN one above the largest number that
/// `base`-<digits>`extension` already has in base's folder (0001 in a folder without any): later
/// saves sort after earlier ones even when some were deleted. Four digits, more once past 9999.
std::filesystem::path nextNumberedFile(const std::string& base, const std::string& extension);

}  // namespace tallow::app
