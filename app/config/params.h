#pragma once
// THE declarations of every renderer parameter (key, type, range, default, units, help), in one
// place: app/params.cpp.
#include <string>
#include <string_view>

#include "app/config/registry.h"
#include "sss/bssrdf/material.h"

namespace tallow::app {

/// The renderer's parameter registry. `materials` supplies the choices of the `material`
/// parameter and the coefficients it sets; the registry keeps its own copy of the table, so it
/// stays valid after `materials` is gone. Built fresh on each call (cheap; no global state): load
/// the table once, build the registry once, and pass both where they are needed.
Registry parameterRegistry(const sss::MaterialTable& materials);

/// The mark a material's name gets when one of its coefficients is edited (material.*).
inline constexpr std::string_view kModifiedSuffix = " (modified)";
/// `name` with kModifiedSuffix (once); "custom" stays "custom" (coefficients that never were measured).
std::string modifiedMaterialName(const std::string& name);

}  // namespace tallow::app
