#pragma once
// The CSV files of `tallow probe bssrdf`: configurations in (one per row, the columns of
// kBssrdfConfigColumns), values out (the same columns plus sd and sd_clamped).
#include <string>
#include <string_view>
#include <vector>

#include "sss/bssrdf/bssrdf.h"

namespace tallow::app {

/// Input header, in this order: x_i, n_i, w_i, x_o, n_o (lengths in mm), σ_a, σ_s (mm⁻¹), g, η.
inline constexpr std::string_view kBssrdfConfigColumns =
    "xi_x,xi_y,xi_z,ni_x,ni_y,ni_z,wi_x,wi_y,wi_z,xo_x,xo_y,xo_z,no_x,no_y,no_z,sigma_a,sigma_s,g,eta";

/// Parses and validates every row (sss::validateBssrdfConfig). Errors throw InputError naming
/// `name:line: …` and the column. Blank lines and a trailing CR are accepted.
std::vector<sss::BssrdfConfig> parseBssrdfConfigs(std::string_view text, const std::string& name);

/// The output CSV: the input columns, then sd (raw) and sd_clamped, each with 17 significant digits
/// so that doubles read back exactly.
std::string formatBssrdfValues(const std::vector<sss::BssrdfConfig>& configs,
                               const std::vector<sss::BssrdfValue>& values);

}  // namespace tallow::app
