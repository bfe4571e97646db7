#pragma once
/** Temporary folders of the tests, removed by RAII (issue 30, item 10: one machine had 1,437
 * dynslam_* folders left in its temporary folder).
 *  - TTempDir: a fresh folder, removed by its destructor;
 *  - tempDir(prefix): a fresh folder kept until the test program ends, then removed by the
 *    registry's destructor (a function-local static: also after a failed test, not after a
 *    crash). For helpers that return a path string.
 * With the environment variable DYNSLAM_KEEP_TEST_DIRS set (to anything), nothing is removed
 * (to look at a failing test's files). Names: <system temp>/dynslam_<prefix>_<pid>. */
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

namespace dynslam_test
{
inline bool keepTestDirs() { return std::getenv("DYNSLAM_KEEP_TEST_DIRS") != nullptr; }

/** A fresh, empty folder <temp>/dynslam_<prefix>_<pid> (removed first if it exists). */
inline std::string makeFreshTempDir(const std::string& prefix)
{
	const auto p = std::filesystem::temp_directory_path() /
	               ("dynslam_" + prefix + "_" + std::to_string(::getpid()));
	std::filesystem::remove_all(p);
	std::filesystem::create_directories(p);
	return p.string();
}

/** Removes a folder tree, ignoring errors (a destructor must not throw). */
inline void removeTempDir(const std::string& path)
{
	if (path.empty() || keepTestDirs()) return;
	std::error_code ec;
	std::filesystem::remove_all(path, ec);
}

/** A fresh folder that lives as long as this object. */
class TTempDir
{
public:
	explicit TTempDir(const std::string& prefix) : m_path(makeFreshTempDir(prefix)) {}
	~TTempDir() { removeTempDir(m_path); }
	TTempDir(const TTempDir&) = delete;
	TTempDir& operator=(const TTempDir&) = delete;
	const std::string& path() const { return m_path; }
	operator const std::string&() const { return m_path; }

private:
	std::string m_path;
};

/** The folders of tempDir(), removed when the program ends. */
class CTempDirRegistry
{
public:
	static CTempDirRegistry& instance()
	{
		static CTempDirRegistry r;
		return r;
	}
	void add(const std::string& p)
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		m_dirs.push_back(p);
	}
	~CTempDirRegistry()
	{
		for (const auto& d : m_dirs) removeTempDir(d);
	}

private:
	CTempDirRegistry() = default;
	std::mutex m_mutex;
	std::vector<std::string> m_dirs;
};

/** A fresh folder <temp>/dynslam_<prefix>_<pid>, removed when the test program ends. */
inline std::string tempDir(const std::string& prefix)
{
	auto& registry = CTempDirRegistry::instance();  // constructed first: destroyed last
	const std::string p = makeFreshTempDir(prefix);
	registry.add(p);
	return p;
}
}  // namespace dynslam_test
