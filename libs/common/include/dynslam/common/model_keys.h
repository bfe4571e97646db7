#pragma once
/** @file model_keys.h
 * The descriptor table of the model's keys: every key with its section, type, default, unit and
 * a one-line description. The core filter's keys are in [DynamicKFSLAM]; each capability module
 * owns its keys in its own section (issue 32 item 2): [ObjectModel] (the object motion model's
 * parameters), [OdometryBias] (the bias block's), [Classify] (the classifier's and the ID -1
 * association's). The switch that enables a module (object_model, odometry_bias,
 * feature_labels) stays in [DynamicKFSLAM]. The table is the list of known keys of every section
 * (TModelOptions::loadFromConfigFile rejects any other, and a module key found in
 * [DynamicKFSLAM] names the section it moved to), the source of doc/configuration.md
 * (writeKeyReference; the test
 * ConfigDoc.CommittedReferenceIsCurrent fails when the committed file is stale) and, through
 * ConfigDoc.DescriptorDefaultsAreTheDumpedDefaults, checked against the defaults that
 * TModelOptions::dumpToTextStream prints. */
#include <iosfwd>
#include <string>
#include <vector>

namespace dynslam
{
/** The sections of the model's keys. kCoreSection is the default section of TModelOptions (a
 * framework back-end's model_section may name another one); the module sections are fixed. */
constexpr const char* kCoreSection = "DynamicKFSLAM";
constexpr const char* kObjectModelSection = "ObjectModel";
constexpr const char* kOdometryBiasSection = "OdometryBias";
constexpr const char* kClassifySection = "Classify";

/** The module sections, in the order of the dump and the reference. */
const std::vector<std::string>& moduleSections();

struct TKeyInfo
{
	std::string key;
	std::string type;        ///< e.g. "real", "int >= 0", "bool", "cartesian | range_bearing"
	std::string def;         ///< the default as dumpToTextStream prints it; "required" if none
	std::string unit;        ///< "-" if none
	std::string what;        ///< one line
	std::string capability;  ///< the group it belongs to (a heading of the reference)
	std::string section = kCoreSection;  ///< kCoreSection or one of moduleSections()
};

/** Every key of every section, in the order of the reference within its section. */
const std::vector<TKeyInfo>& modelKeys();

/** The names of modelKeys(). */
std::vector<std::string> modelKeyNames();

/** The names of the keys of `section` (kCoreSection or a module section); empty if unknown. */
std::vector<std::string> sectionKeyNames(const std::string& section);

/** The section of `key` (case-insensitive, as MRPT's reader), or "" if no section has it. */
std::string sectionOfKey(const std::string& key);

/** A profile and the keys it sets (with their values), each with its section. */
struct TProfileKeys
{
	std::string name;  ///< e.g. "paper" (config/profiles/paper.ini)
	struct TSetting
	{
		std::string section, key, value;
	};
	std::vector<TSetting> keys;
};

/** Writes the markdown key reference (doc/configuration.md's generated part) to `out`: per
 * section its key count and one table per capability, the column "profiles" from `profiles`. */
void writeKeyReference(std::ostream& out, const std::vector<TProfileKeys>& profiles);
}  // namespace dynslam
