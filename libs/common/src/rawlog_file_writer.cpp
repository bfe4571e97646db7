#include <dynslam/common/rawlog_file_writer.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/serialization/CArchive.h>

#include <stdexcept>

namespace dynslam
{
struct CRawlogFileWriter::Impl
{
	mrpt::io::CFileGZOutputStream file;
};

CRawlogFileWriter::CRawlogFileWriter(const std::string& path, const std::string& who)
    : m(std::make_unique<Impl>())
{
	if (!m->file.open(path)) throw std::runtime_error(who + ": cannot write " + path);
}

CRawlogFileWriter::~CRawlogFileWriter() = default;

void CRawlogFileWriter::writeComment(const std::string& text, mrpt::Clock::time_point stamp)
{
	mrpt::obs::CObservationComment c;
	c.text = text;
	c.timestamp = stamp;
	c.sensorLabel = "COMMENT";
	mrpt::serialization::archiveFrom(m->file) << c;
}

void CRawlogFileWriter::writeStep(const mrpt::obs::CActionCollection& acts,
                                  const mrpt::obs::CSensoryFrame& sf)
{
	auto ar = mrpt::serialization::archiveFrom(m->file);
	ar << acts << sf;
}

void CRawlogFileWriter::close() { m->file.close(); }
}  // namespace dynslam
