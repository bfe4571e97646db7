#pragma once
/** @file config_utils.h
 * Strict INI reading on top of mrpt::config::CConfigFileBase: required keys throw when
 * missing, and every invalid value is rejected with a message naming section, key and value.
 * Shared by every TOptions of the project. */
#include <mrpt/config/CConfigFileBase.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace dynslam::config
{
/** Throws std::invalid_argument("[section] key = 'value': what"). */
[[noreturn]] void fail(const std::string& section, const std::string& key, const std::string& value,
                       const std::string& what);

bool has(const mrpt::config::CConfigFileBase& c, const std::string& section,
         const std::string& key);
/** Raw string of a required key (throws if missing or empty). */
std::string requireString(const mrpt::config::CConfigFileBase& c, const std::string& section,
                          const std::string& key);

/** Scalars: `required` throws when the key is missing; otherwise `def` is returned.
 * Values that do not parse completely are rejected. */
double readDouble(const mrpt::config::CConfigFileBase& c, const std::string& section,
                  const std::string& key, double def, bool required = false);
long readInt(const mrpt::config::CConfigFileBase& c, const std::string& section,
             const std::string& key, long def, bool required = false);
bool readBool(const mrpt::config::CConfigFileBase& c, const std::string& section,
              const std::string& key, bool def, bool required = false);
std::string readString(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::string& key, const std::string& def, bool required = false);

/** Range checks with the same message style. */
double readPositive(const mrpt::config::CConfigFileBase& c, const std::string& section,
                    const std::string& key, double def, bool required = false);
double readNonNegative(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::string& key, double def, bool required = false);

/** A vector `[a b c]` (or `a b c`, commas allowed) of exactly n numbers. */
Eigen::VectorXd readVector(const mrpt::config::CConfigFileBase& c, const std::string& section,
                           const std::string& key, const Eigen::VectorXd& def, int n,
                           bool required = false);

/** A dim x dim covariance, written either as its diagonal `[a b c]` (dim numbers) or as the
 * full matrix `[a b; c d]` / dim*dim numbers. Must be finite, symmetric and positive definite
 * (positive semi-definite with allowSingular). */
Eigen::MatrixXd readCovariance(const mrpt::config::CConfigFileBase& c, const std::string& section,
                               const std::string& key, const Eigen::MatrixXd& def, int dim,
                               bool required = false, bool allowSingular = false);

/** One of a fixed list of words (case-insensitive); returns its index. */
int readChoice(const mrpt::config::CConfigFileBase& c, const std::string& section,
               const std::string& key, const std::vector<std::string>& choices, int def,
               bool required = false);

/** Throws if the section holds a key that is not in `known` (catches misspelled keys). */
void rejectUnknownKeys(const mrpt::config::CConfigFileBase& c, const std::string& section,
                       const std::vector<std::string>& known);

/** Formats a matrix for dumpToTextStream: `[a b; c d]`. */
std::string formatMatrix(const Eigen::MatrixXd& m);
}  // namespace dynslam::config
