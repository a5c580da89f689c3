// Who may use a preview server: it listens on 127.0.0.1 only, and a request is answered only
// when its Host header names that address (or localhost) with the server's port (a page of
// another site cannot reach it through a DNS name rebound to 127.0.0.1) and it carries the
// session's token, 128 random bits from the system's random device printed in the URL.
#pragma once
#include <string>

namespace penink {

// 32 lower-case hex digits from std::random_device (the kernel's random source on Linux).
std::string random_token();

// "127.0.0.1:PORT" or "localhost:PORT" (letters in any case), nothing else.
bool host_allowed(const std::string& host, int port);

// The same as `token`, compared in time independent of where they differ; an empty `token`
// matches nothing.
bool token_matches(const std::string& given, const std::string& token);

}  // namespace penink
