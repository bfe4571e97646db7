#pragma once
/** @file number_format.h
 * Numbers written to text files (INI, CSV) so that they read back to the same double. */
#include <string>

namespace dynslam::io
{
/** The shortest of 15..17 significant digits ("%.*g") that reads back (strtod) to exactly v. */
std::string formatShortest(double v);
}  // namespace dynslam::io
