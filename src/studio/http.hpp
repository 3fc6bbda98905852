#pragma once
// cpp-httplib, for the studio's files that need it (internal to src/studio). Its header includes
// glibc's <resolv.h>, whose `#define _res (*__res_state())` renames Eigen's parameters of that
// name in every header read afterwards (a unity batch, or a file that includes Eigen later):
// nothing of ours uses the resolver's state, so the macro goes.
#include <httplib.h>
#undef _res
