/** The DETECTION_BOXES rawlog comment (dynslam/common/detection_boxes.h, issue 31 item 1): an exact
 * round trip (also through MRPT's serialization), every malformed line a std::runtime_error
 * naming the line, the corners by hand, and the step-input parser's boxes with their
 * group/corner consistency check (dynslam/common/step_input.h). */
#include <dynslam/common/detection_boxes.h>
#include <dynslam/common/detection_groups.h>
#include <dynslam/common/odometry_action.h>
#include <dynslam/common/step_input.h>
#include <gtest/gtest.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <functional>
#include <limits>

using namespace dynslam;
using estimator::TBoxDetection;

namespace
{
TBoxDetection box(int32_t g, const std::string& cls, double score, double x, double y, double yaw,
                  double l, double w)
{
	TBoxDetection b;
	b.group = g;
	b.cls = cls;
	b.score = score;
	b.pose = Eigen::Vector3d(x, y, yaw);
	b.extent = Eigen::Vector2d(l, w);
	return b;
}

std::vector<TBoxDetection> someBoxes()
{
	return {box(0, "Car", 0.1 + 0.2, 1.0 / 3, -7.123456789012345e1, -M_PI, 4.1, 1.7),
	        box(5, "Cyclist", -2.5e-300, 39.999999999999993, 1e-17, 3.0 * M_PI / 7, 1.9, 0.6),
	        box(12, "Pedestrian", 9.87654321e8, -0.0, 2.0 / 3, 1e-9, 0.8, 0.6000000000000001)};
}

void expectSame(const TBoxDetection& a, const TBoxDetection& b)
{
	EXPECT_EQ(a.group, b.group);
	EXPECT_EQ(a.cls, b.cls);
	EXPECT_EQ(a.score, b.score);  // exact: 17 significant digits
	for (int i = 0; i < 3; ++i) EXPECT_EQ(a.pose[i], b.pose[i]) << i;
	for (int i = 0; i < 2; ++i) EXPECT_EQ(a.extent[i], b.extent[i]) << i;
}

/** A step whose bearing-range observation holds the corners of `boxes` (ID -1, in the order of
 * boxCorners) after two labelled readings (IDs 3 and 8, no group), the DETECTION_GROUPS and the
 * DETECTION_BOXES comments. `drop`: corners of the first box not written; `relabel`: the ID of
 * the first box's first corner. */
mrpt::obs::CSensoryFrame::Ptr stepFrame(const std::vector<TBoxDetection>& boxes, int drop = 0,
                                        int32_t relabel = -1, bool withObs = true)
{
	auto obs = mrpt::obs::CObservationBearingRange::Create();
	std::vector<int32_t> ids, groups;
	auto add = [&](const Eigen::Vector2d& p, int32_t id, int32_t g)
	{
		mrpt::obs::CObservationBearingRange::TMeasurement m;
		m.range = float(p.norm());
		m.yaw = float(std::atan2(p.y(), p.x()));
		m.pitch = 0;
		m.landmarkID = id;
		obs->sensedData.push_back(m);
		ids.push_back(id);
		groups.push_back(g);
	};
	add({5, 1}, 3, -1);
	add({6, -2}, 8, -1);
	for (size_t i = 0; i < boxes.size(); ++i)
	{
		const auto c = boxCorners(boxes[i]);
		for (size_t j = 0; j < 4; ++j)
		{
			if (i == 0 && int(j) >= 4 - drop) continue;
			add(c[j], i == 0 && j == 0 ? relabel : -1, boxes[i].group);
		}
	}
	auto sf = mrpt::obs::CSensoryFrame::Create();
	if (withObs) sf->insert(obs);
	sf->insert(makeDetectionGroups(ids, groups));
	sf->insert(makeDetectionBoxes(boxes));
	return sf;
}

estimator::TStepInput parse(const mrpt::obs::CSensoryFrame::Ptr& sf)
{
	return parseStepInput(
	    makeOdometryAction(Eigen::Vector3d(1, 0, 0), 1e-4 * Eigen::Matrix3d::Identity()), sf,
	    TParseOptions(), "step 7");
}

/** readDetectionBoxes of a comment with `text`; the error message ("" if none). */
std::string readError(const std::string& text)
{
	mrpt::obs::CSensoryFrame sf;
	auto c = mrpt::obs::CObservationComment::Create();
	c->text = text;
	sf.insert(c);
	try
	{
		readDetectionBoxes(sf, "step 3");
	}
	catch (const std::runtime_error& e)
	{
		return e.what();
	}
	return "";
}

void expectLineError(const std::string& line, const std::string& part)
{
	const std::string e = readError("DETECTION_BOXES\n# c\n0 Car 1 2 3 0.5 4 2\n" + line + "\n");
	EXPECT_NE(e.find("step 3: DETECTION_BOXES comment, line 4 '" + line + "'"), std::string::npos)
	    << e;
	EXPECT_NE(e.find(part), std::string::npos) << "'" << e << "' lacks '" << part << "'";
}
}  // namespace

TEST(DetectionBoxes, RoundTripIsExact)
{
	const auto boxes = someBoxes();
	const auto c = makeDetectionBoxes(boxes);
	EXPECT_EQ(c->sensorLabel, kDetectionBoxesLabel);
	mrpt::obs::CSensoryFrame sf;
	sf.insert(c);
	// through MRPT's serialization, as in a rawlog
	mrpt::io::CMemoryStream buf;
	auto ar = mrpt::serialization::archiveFrom(buf);
	ar << sf;
	buf.Seek(0);
	mrpt::obs::CSensoryFrame back;
	ar >> back;
	const auto got = readDetectionBoxes(back, "test");
	ASSERT_EQ(got.size(), boxes.size());
	for (size_t i = 0; i < boxes.size(); ++i) expectSame(got[i], boxes[i]);
	EXPECT_TRUE(std::signbit(got[2].pose.x())) << "-0 stays -0";
	EXPECT_TRUE(readDetectionBoxes(mrpt::obs::CSensoryFrame(), "test").empty());
	// an empty step: the comment with no box
	mrpt::obs::CSensoryFrame empty;
	empty.insert(makeDetectionBoxes({}));
	EXPECT_TRUE(readDetectionBoxes(empty, "test").empty());
}

TEST(DetectionBoxes, MalformedLinesNameTheLine)
{
	EXPECT_EQ(readError("DETECTION_BOXES\r\n\n  # comment\n0 Car 1 2 3 0.5 4 2\r\n"), "");
	EXPECT_EQ(readError("another comment\n0 Car 1 2\n"), "") << "another comment is ignored";
	expectLineError("1 Car 1 2 3 0.5 4", "expected 8 columns");
	expectLineError("1 Car 1 2 3 0.5 4 2 9", "<width>', found 9");
	expectLineError("1.5 Car 1 2 3 0.5 4 2", "group '1.5' is not an integer");
	expectLineError("x Car 1 2 3 0.5 4 2", "group 'x' is not an integer");
	expectLineError("-1 Car 1 2 3 0.5 4 2", "group -1 (an ID >= 0)");
	expectLineError("3000000000 Car 1 2 3 0.5 4 2", "group 3000000000 (an ID >= 0)");
	expectLineError("1 Car high 2 3 0.5 4 2", "score 'high' is not a number");
	expectLineError("1 Car 1 2x 3 0.5 4 2", "x '2x' is not a number");
	expectLineError("1 Car 1 2 nan 0.5 4 2", "y 'nan' is not finite");
	expectLineError("1 Car 1 2 3 inf 4 2", "yaw 'inf' is not finite");
	expectLineError("1 Car NaN 2 3 0.5 4 2", "score 'NaN' is not finite");
	expectLineError("1 Car 1 2 3 0.5 0 2", "length and width must be > 0");
	expectLineError("1 Car 1 2 3 0.5 4 -2", "length and width must be > 0");
	expectLineError("0 Van 1 2 3 0.5 4 2", "group 0 repeated");
	EXPECT_EQ(readError("DETECTION_BOXES\n1 Car 1 2 3 0.5 1e-300 2\n"), "") << "tiny > 0";
}

TEST(DetectionBoxes, MakeRejectsBadBoxes)
{
	auto b = someBoxes();
	EXPECT_NO_THROW(makeDetectionBoxes(b));
	auto bad = [&](const std::function<void(TBoxDetection&)>& f)
	{
		auto v = someBoxes();
		f(v[1]);
		EXPECT_THROW(makeDetectionBoxes(v), std::invalid_argument);
	};
	bad([](TBoxDetection& x) { x.group = -1; });
	bad([](TBoxDetection& x) { x.group = 0; });  // repeated
	bad([](TBoxDetection& x) { x.cls = ""; });
	bad([](TBoxDetection& x) { x.cls = "Big Car"; });
	bad([](TBoxDetection& x) { x.score = std::numeric_limits<double>::quiet_NaN(); });
	bad([](TBoxDetection& x) { x.pose.z() = std::numeric_limits<double>::infinity(); });
	bad([](TBoxDetection& x) { x.extent.x() = 0; });
	bad([](TBoxDetection& x) { x.extent.y() = -1; });
}

TEST(DetectionBoxes, CornersByHand)
{
	// centre (1, 2), heading +90 deg: the length axis u = (0, 1), its left v = (-1, 0)
	const auto c = boxCorners(box(0, "Car", 1, 1, 2, M_PI / 2, 4, 2));
	ASSERT_EQ(c.size(), 4u);
	const Eigen::Vector2d want[4] = {{0, 4}, {2, 4}, {2, 0}, {0, 0}};  // FL, FR, RR, RL
	for (int j = 0; j < 4; ++j) EXPECT_LT((c[size_t(j)] - want[j]).norm(), 1e-12) << j;
	// yaw + pi: the same footprint, corners in the opposite order (FL <-> RR, FR <-> RL)
	const auto f = boxCorners(box(0, "Car", 1, 1, 2, -M_PI / 2, 4, 2));
	EXPECT_LT((f[0] - want[2]).norm(), 1e-12);
	EXPECT_LT((f[1] - want[3]).norm(), 1e-12);
}

TEST(DetectionBoxes, ParserFillsTheBoxesAndChecksTheCorners)
{
	const auto boxes = someBoxes();
	const auto in = parse(stepFrame(boxes));
	ASSERT_EQ(in.boxes.size(), 3u);
	for (size_t i = 0; i < 3; ++i) expectSame(in.boxes[i], boxes[i]);
	ASSERT_EQ(in.readings.size(), 2u + 12u);
	EXPECT_EQ(in.readings[0].id, 3);
	EXPECT_EQ(in.readings[0].hint, -1);
	for (size_t i = 0; i < 3; ++i)
	{
		const auto c = boxCorners(boxes[i]);
		for (size_t j = 0; j < 4; ++j)
		{
			const auto& r = in.readings[2 + 4 * i + j];
			EXPECT_EQ(r.id, -1);
			EXPECT_EQ(r.hint, boxes[i].group);
			// Cartesian model: z is the corner (float range and bearing in the observation)
			EXPECT_LT((r.z - c[j]).norm(), 1e-4 * (1 + c[j].norm())) << i << " " << j;
		}
	}
	// a sensory frame without the comment: no boxes (and the readings as before)
	auto plain = stepFrame({});
	EXPECT_TRUE(parse(plain).boxes.empty());
	EXPECT_EQ(parse(plain).readings.size(), 2u);

	auto expectError = [](const mrpt::obs::CSensoryFrame::Ptr& sf, const std::string& part)
	{
		try
		{
			parse(sf);
			ADD_FAILURE() << "accepted";
		}
		catch (const std::runtime_error& e)
		{
			EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
		}
	};
	expectError(stepFrame(boxes, 1),
	            "step 7: DETECTION_BOXES box 0 (group 0, Car): 3 readings with that detection "
	            "group, 3 of them with landmark ID -1");
	expectError(stepFrame(boxes, 0, 17),
	            "box 0 (group 0, Car): 4 readings with that detection "
	            "group, 3 of them with landmark ID -1");
	expectError(stepFrame(boxes, 4), "box 0 (group 0, Car): 0 readings");
	expectError(stepFrame(boxes, 0, -1, false), "box 0 (group 0, Car): 0 readings");
	// eight readings in group 0: box 9's corners re-pointed to group 0 in the groups comment
	const auto b0 = boxes[0];
	const auto two = stepFrame({b0, box(9, "Car", 1, 3, 3, 0, 4, 2)});
	auto eight = mrpt::obs::CSensoryFrame::Create();
	for (const auto& o : *two)
		if (!std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(o)) eight->insert(o);
	std::vector<int32_t> ids(10, -1), groups(10, 0);
	ids[0] = 3, ids[1] = 8, groups[0] = groups[1] = -1;
	eight->insert(makeDetectionGroups(ids, groups));
	eight->insert(makeDetectionBoxes({b0}));
	expectError(eight, "box 0 (group 0, Car): 8 readings");
	// without boxes, ID -1 readings with a group are allowed (as before)
	mrpt::obs::CSensoryFrame::Ptr noBoxes = mrpt::obs::CSensoryFrame::Create();
	for (const auto& o : *eight)
		if (!std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(o) ||
		    o->sensorLabel != kDetectionBoxesLabel)
			noBoxes->insert(o);
	const auto nb = parse(noBoxes);
	EXPECT_TRUE(nb.boxes.empty());
	EXPECT_EQ(nb.readings[5].hint, 0);
}
