#pragma once
/** @file rawlog_file_writer.h
 * The one rawlog writer of the project (simulator, MRCLAM and KITTI importers): a gzip-compressed
 * MRPT rawlog in format #1 (action collection / sensory frame pairs), optionally preceded by a
 * CObservationComment, as MRPT's own tools write it. */
#include <mrpt/core/Clock.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <memory>
#include <string>

namespace dynslam
{
class CRawlogFileWriter
{
public:
	/** Opens `path` for writing; throws std::runtime_error("who: cannot write path"). */
	CRawlogFileWriter(const std::string& path, const std::string& who);
	~CRawlogFileWriter();
	CRawlogFileWriter(const CRawlogFileWriter&) = delete;
	CRawlogFileWriter& operator=(const CRawlogFileWriter&) = delete;

	/** A CObservationComment (sensorLabel "COMMENT") with `text` and time stamp `stamp`. */
	void writeComment(const std::string& text, mrpt::Clock::time_point stamp);
	/** One step: the action collection, then the sensory frame. */
	void writeStep(const mrpt::obs::CActionCollection& acts, const mrpt::obs::CSensoryFrame& sf);
	/** Flushes and closes the file (also done by the destructor). */
	void close();

private:
	struct Impl;
	std::unique_ptr<Impl> m;
};
}  // namespace dynslam
