/** Soak: a long run on the endless straight track (bench/synthetic_world.h) with the drop
 * policies on. Every 500 steps the covariance must be symmetric and positive semi-definite; the
 * state size must stay bounded and the resident memory must not grow with the steps.
 * Steps: DYNSLAM_SOAK_STEPS (default 20,000 in ctest; the 100,000-step run of
 * doc/robustness.md is DYNSLAM_SOAK_STEPS=100000 hardening_tests --gtest_filter=Soak.*). */
#include <dynslam/ekf/CDynamicKFSLAM2D.h>
#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "alloc_stats.h"
#include "straight_track.h"

using namespace dynslam;

namespace
{
long rssKb()
{
	std::ifstream f("/proc/self/statm");
	long size = 0, resident = 0;
	if (!(f >> size >> resident)) return -1;
	return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

int soakSteps()
{
	const char* s = std::getenv("DYNSLAM_SOAK_STEPS");
	return s ? std::max(1000, std::atoi(s)) : 20000;
}
}  // namespace

TEST(Soak, LongRunStaysSymmetricPsdAndBounded)
{
	const int steps = soakSteps();
	const dynslam_bench::TSyntheticOptions o = dynslam_test::straightTrack(7);
	dynslam_bench::CSyntheticWorld world(o);
	CDynamicKFSLAM2D f;
	dynslam_test::configureForStraightTrack(f, o);
	f.options.smoothing = true;
	f.options.keep_last_poses = 3;
	f.reset();

	long rssAt1000 = -1, rssEnd = -1, heapAt1000 = -1;
	Eigen::Index maxDim = 0, dimAt1000 = 0;
	double worstAsym = 0, worstNeg = 0;
	for (int k = 0; k < steps; ++k)
	{
		mrpt::obs::CActionCollection::Ptr a;
		mrpt::obs::CSensoryFrame::Ptr sf;
		world.next(a, sf);
		ASSERT_NO_THROW(f.processActionObservation(a, sf)) << "step " << k;
		const Eigen::Index dim = f.fullMean().size();
		maxDim = std::max(maxDim, dim);
		if (k == 1000)
		{
			dimAt1000 = dim;
			malloc_trim(0);  // see the memory check below
			rssAt1000 = rssKb();
			heapAt1000 = dynslam_test::allocatedBytes() / 1024;
		}
		if (k % (steps / 10) == 0)
		{
			const long before = rssKb();
			malloc_trim(0);
			std::cout << "step " << k << ": RSS " << before << " kB, after malloc_trim " << rssKb()
			          << " kB, heap in use " << mallinfo2().uordblks / 1024 << " kB, free in heap "
			          << mallinfo2().fordblks / 1024 << " kB, state dim " << dim << "\n";
		}
		if (k % 500 == 0 || k == steps - 1)
		{
			const Eigen::MatrixXd P = f.fullCov().asEigen();
			ASSERT_TRUE(P.allFinite()) << "step " << k;
			const double scale = P.cwiseAbs().maxCoeff();
			const double asym = (P - P.transpose()).cwiseAbs().maxCoeff() / scale;
			const double minEig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(
			                          0.5 * (P + P.transpose()), Eigen::EigenvaluesOnly)
			                          .eigenvalues()
			                          .minCoeff();
			worstAsym = std::max(worstAsym, asym);
			worstNeg = std::max(worstNeg, -minEig / scale);
			ASSERT_LE(asym, 1e-12) << "step " << k;
			ASSERT_GE(minEig, -1e-12 * scale) << "step " << k;
			ASSERT_TRUE(f.fullMean().asEigen().allFinite()) << "step " << k;
		}
	}
	// Memory allocated (alloc_stats.h: in use plus mmapped, or ASan's count): the covariance is
	// bounded; what grows are the records of dropped landmarks and poses (3 poses of ~104 bytes
	// and half a landmark per step here, kept for the results). Bound: 1 kB per step. The RSS is
	// printed (doc/robustness.md); SoakMemory.* checks record_dropped = false.
	const long heapEnd = dynslam_test::allocatedBytes() / 1024;
	malloc_trim(0);
	rssEnd = rssKb();
	std::cout << "allocated at step 1000 " << heapAt1000 << " kB, at the end " << heapEnd
	          << " kB; RSS after malloc_trim at step 1000 " << rssAt1000 << " kB, at the end "
	          << rssEnd << " kB\n";
	EXPECT_LT(heapEnd - heapAt1000, (steps - 1000) + 1024);

	// The ego follows the truth (no divergence over the long run): within 1% of the distance.
	const Eigen::Vector3d truth = world.truePose();
	const auto est = f.getEgoPose();
	const double dist = o.step_length * (steps - 1);
	EXPECT_LT(std::hypot(est.mean.x() - truth.x(), est.mean.y() - truth.y()), 0.01 * dist);
	std::cout << "soak: " << steps << " steps, state dim at 1000 " << dimAt1000 << ", max "
	          << maxDim << ", final " << f.fullMean().size() << "; worst asymmetry " << worstAsym
	          << ", worst negative eigenvalue / max|P| " << worstNeg << "; dropped static "
	          << f.getDroppedStaticLandmarks().size() << "\n";
	// Bounded state: what is in range (~12 landmarks, 3 objects with 3 poses) plus the drop window.
	EXPECT_LE(maxDim, 3 + 2 * (40 + 3 * (3 + 2 * 3)));
}
