#pragma once
// Who may talk to a studio server: the checks every request passes before any handler runs.
//
// The server binds the loopback address unless told otherwise, so other machines cannot reach it;
// what remains are other users of this machine and web pages open in the user's own browser. The
// first are kept out by a random token (as Jupyter does): the URL the studio prints carries it,
// the page's first request turns it into a cookie, and a request without it is refused. The
// second (a page of another site that makes the browser call 127.0.0.1, or a DNS name rebound to
// it) are kept out by the Host header, which must name the loopback with the studio's port, and
// by the cookie being SameSite=Strict.
#include <string>
#include <string_view>

namespace cropsight::studio {

/// A new token: 32 hex digits (128 bits) from std::random_device (the kernel's random source).
std::string new_token();

/// Compares two tokens in time that depends on their length only (a timing side channel must not
/// reveal a token's prefix to another local user).
bool same_token(std::string_view a, std::string_view b);

/// Whether a request's Host header names this server: "localhost", "127.0.0.1" or "[::1]" with
/// `port`, or `bind_address` with `port` when the studio was bound to another address on purpose
/// (--bind). A Host without the port, or naming any other host, is refused (DNS rebinding).
bool host_allowed(std::string_view host, int port, std::string_view bind_address);

/// The value of cookie `name` in a Cookie header ("a=1; b=2"); empty when absent.
std::string cookie_value(std::string_view cookie_header, std::string_view name);

/// The cookie that carries the token of the studio on `port` (cookies ignore ports, so two studios
/// on one machine need distinct names).
std::string token_cookie_name(int port);

}  // namespace cropsight::studio
