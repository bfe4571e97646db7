#include <dynslam/apps/step_timing.h>
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace dynslam::apps
{
void fillStateSize(const ISlamBackend& backend, TStepTiming& t)
{
	if (const auto* ekf = dynamic_cast<const CDynamicKFSLAM2D*>(&backend))
	{
		t.static_landmarks = ekf->staticLandmarkCount();
		t.live_objects = ekf->liveObjectCount();
		t.state_dim = ekf->workingDim();
		return;
	}
	t.static_landmarks = backend.getStaticLandmarks().size();
	t.live_objects = 0;
	for (const auto& [obj, track] : backend.getObjectTracks())
		for (const auto& p : track.poses)
			if (p.in_state)
			{
				++t.live_objects;
				break;
			}
	t.state_dim = 0;
}

namespace
{
std::string freshTempPath()
{
	static std::atomic<unsigned> counter{0};
	const std::filesystem::path dir = std::filesystem::temp_directory_path();
	return (dir / ("dynslam-run-timing-" + std::to_string(::getpid()) + "-" +
	               std::to_string(counter++) + ".csv"))
	    .string();
}
}  // namespace

CTimingCsv::CTimingCsv() : m_temp(freshTempPath())
{
	m_os.open(m_temp, std::ios::out | std::ios::trunc);
	if (!m_os) throw std::runtime_error("cannot write the temporary file '" + m_temp + "'");
	m_os << "step,ms,static_landmarks,live_objects,state_dim\n";
}

CTimingCsv::~CTimingCsv()
{
	if (m_moved) return;
	m_os.close();
	std::error_code ec;
	std::filesystem::remove(m_temp, ec);
}

void CTimingCsv::write(const TStepTiming& t)
{
	char ms[32];
	std::snprintf(ms, sizeof(ms), "%.6f", t.ms);
	m_os << t.step << "," << ms << "," << t.static_landmarks << "," << t.live_objects << ",";
	if (t.state_dim > 0) m_os << t.state_dim;
	m_os << "\n";
}

void CTimingCsv::moveTo(const std::string& path)
{
	m_os.close();
	if (m_os.fail()) throw std::runtime_error("writing '" + m_temp + "' failed");
	std::error_code ec;
	std::filesystem::rename(m_temp, path, ec);
	if (ec)  // another file system: copy, then remove
	{
		std::filesystem::copy_file(m_temp, path, std::filesystem::copy_options::overwrite_existing,
		                           ec);
		if (ec) throw std::runtime_error("cannot write '" + path + "': " + ec.message());
		std::filesystem::remove(m_temp, ec);
	}
	m_moved = true;
}
}  // namespace dynslam::apps
