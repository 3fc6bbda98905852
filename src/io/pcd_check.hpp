#pragma once
// Internal to io: a PCD header checked before PCL reads it. PCL 1.13's PCDReader::readHeader
// sizes the point buffer from WIDTH x HEIGHT x (the SIZE x COUNT sum) before it reads any data,
// so a COUNT or WIDTH of 2^40 made it allocate 21 GB (fuzz_pcd; fuzz/regressions/pcd/). The
// header lines PCL reads are checked here: FIELDS, SIZE, TYPE and COUNT with one entry per
// field (SIZE 1, 2, 4 or 8; TYPE I, U or F; COUNT 1 to 2^20), WIDTH, HEIGHT and POINTS plain
// integers with POINTS = WIDTH x HEIGHT, and a body that can hold them: an ascii value takes at
// least two bytes, a binary point its full size, a compressed body at most 1 GiB. PCL reads a
// line's keyword by prefix and goes on reading header lines after DATA until one is not a
// keyword; the check reads the lines the same way and refuses a keyword line after DATA (body
// bytes that read as "COLUMNS ..." redefined the fields after the checks: a read 2 GB past the
// buffer, fuzz_pcd), a keyword given twice, a line PCL does not know before DATA, and FIELDS,
// SIZE, TYPE or COUNT after POINTS (PCL sizes the point buffer at POINTS: a write past it).
#include <string>

namespace cropsight::io::detail {

/// Throws Error(where, ...) naming the first problem of PCD file contents `bytes`.
void check_pcd_header(const std::string& bytes, const std::string& where);

}  // namespace cropsight::io::detail
