#pragma once
// The page's files (src/studio/web/), compiled into the library at build time by
// src/studio/embed_web.cmake: the studio serves them from memory, so it reads no file of its
// install to serve the page and no request can name one.
#include <span>
#include <string_view>

namespace cropsight::studio {

struct WebAsset {
  std::string_view name;  ///< file name in src/studio/web/, e.g. "studio.js"
  std::string_view bytes;
};

/// Every file of the page.
std::span<const WebAsset> web_assets();

}  // namespace cropsight::studio
