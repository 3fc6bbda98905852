// Token, Host and cookie checks of the studio server (studio/access.hpp).
#include "cropsight/studio/access.hpp"

#include <cstdint>
#include <random>

namespace cropsight::studio {

std::string new_token() {
  std::random_device source;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (int k = 0; k < 4; ++k) {
    std::uint32_t word = source();
    for (int d = 0; d < 8; ++d, word >>= 4) token += kHex[word & 0xf];
  }
  return token;
}

bool same_token(std::string_view a, std::string_view b) {
  if (a.size() != b.size() || a.empty()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

bool host_allowed(std::string_view host, int port, std::string_view bind_address) {
  const std::string suffix = ":" + std::to_string(port);
  if (host.size() <= suffix.size() || host.substr(host.size() - suffix.size()) != suffix) return false;
  const std::string_view name = host.substr(0, host.size() - suffix.size());
  if (name == "localhost" || name == "127.0.0.1" || name == "[::1]") return true;
  const bool wildcard = bind_address == "0.0.0.0" || bind_address == "::" || bind_address.empty();
  return !wildcard && name == bind_address;
}

std::string cookie_value(std::string_view header, std::string_view name) {
  std::size_t pos = 0;
  while (pos < header.size()) {
    std::size_t end = header.find(';', pos);
    if (end == std::string_view::npos) end = header.size();
    std::string_view pair = header.substr(pos, end - pos);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    const std::size_t eq = pair.find('=');
    if (eq != std::string_view::npos && pair.substr(0, eq) == name) return std::string(pair.substr(eq + 1));
    pos = end + 1;
  }
  return {};
}

std::string token_cookie_name(int port) { return "cropsight_studio_" + std::to_string(port); }

}  // namespace cropsight::studio
