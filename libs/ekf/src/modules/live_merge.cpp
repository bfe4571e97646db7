/** The live-merge module (live_merge.h). */
#include "live_merge.h"

#include <dynslam/core/models/live_merge.h>
#include <dynslam/core/models/object_merge.h>
#include <dynslam/estimator/seam_registries.h>

#include <Eigen/Cholesky>
#include <utility>

#include "../index_append.h"
#include "state_surgery.h"

namespace dynslam::ekf
{
using estimator::BlockKind;

namespace
{
/** An object that may take part in a live merge this step: its newest pose, velocity (cv) and
 * f_0 blocks (in feature-set order, founders first) and its reference point in the world. */
struct TLive
{
	int32_t obj = -1;
	int dim = 0, founders = 0;
	size_t pose = SIZE_MAX, vel = SIZE_MAX;
	std::vector<size_t> f0;
	Eigen::Vector2d p = Eigen::Vector2d::Zero();
};

/** The objects seen in this step that have a pose of this step (paper) or a velocity (cv) and an
 * f_0 for every feature. */
std::vector<TLive> liveObjects(const estimator::CPaddedLayout& L,
                               const estimator::CObjectRegistry& reg, const Eigen::VectorXd& x,
                               int step, bool objectCentric, const std::set<int32_t>& seen)
{
	std::map<int32_t, TLive> by;
	std::map<int32_t, std::map<int32_t, size_t>> f0;  // object -> feature ID -> block
	for (size_t b = 0; b < L.size(); ++b)
	{
		const estimator::TBlock& t = L[b];
		if (!seen.count(t.object) || !reg.has(t.object)) continue;
		TLive& o = by[t.object];
		if (t.kind == BlockKind::ObjectPose && (o.pose == SIZE_MAX || L[o.pose].step <= t.step))
			o.pose = b;
		else if (t.kind == BlockKind::ObjectVelocity)
			o.vel = b;
		else if (t.kind == BlockKind::ObjectFeature0)
			f0[t.object][t.id] = b;
	}
	std::vector<TLive> out;
	for (auto& [obj, o] : by)
	{
		const estimator::TObjectEntry& e = reg.at(obj);
		if (o.pose == SIZE_MAX || (objectCentric ? o.vel == SIZE_MAX : L[o.pose].step != step))
			continue;
		o.obj = obj;
		o.dim = e.poseDim();
		o.founders = e.founders;
		bool all = true;
		for (const int32_t id : e.feature_ids)
		{
			const auto it = f0[obj].find(id);
			if (it == f0[obj].end())
				all = false;
			else
				o.f0.push_back(it->second);
		}
		if (!all || o.f0.empty() || o.founders < 1) continue;
		for (int k = 0; k < o.founders; ++k) o.p += x.segment(L.first(o.f0[size_t(k)]), 2);
		o.p = o.p / double(o.founders) + x.segment(L.first(o.pose), 2);
		out.push_back(o);
	}
	return out;
}

}  // namespace

/** The live-merge sample of B in A's frame (A has a 3-dof pose). */
static estimator::TLiveMergeSample liveSample(const estimator::CPaddedLayout& L,
                                              const Eigen::VectorXd& x,
                                              const ekf::CSquareBuffer::ConstView& P,
                                              const TLive& A, const TLive& B, int step)
{
	// Inputs: [xi_A; A's founders' f_0; xi_B; B's f_0 (all); v_A; v_B].
	std::vector<int> in = L.indices(A.pose);
	for (int k = 0; k < A.founders; ++k) ekf::appendIndices(in, L.indices(A.f0[size_t(k)]));
	const Eigen::Index cxiB = Eigen::Index(in.size());
	ekf::appendIndices(in, L.indices(B.pose));
	const Eigen::Index cfB = Eigen::Index(in.size());
	for (const size_t b : B.f0) ekf::appendIndices(in, L.indices(b));
	const Eigen::Index cvA = Eigen::Index(in.size());
	const bool vel = A.vel != SIZE_MAX && B.vel != SIZE_MAX;
	if (vel)  // the velocities: the blocks' first entries (ca: then the acceleration)
	{
		const std::vector<int> vA = L.indices(A.vel), vB = L.indices(B.vel);
		ekf::appendIndices(in, std::vector<int>(vA.begin(), vA.begin() + 3));
		ekf::appendIndices(in, std::vector<int>(vB.begin(), vB.begin() + B.dim));
	}
	const Eigen::Index n = Eigen::Index(in.size()), m = Eigen::Index(B.f0.size());
	Eigen::VectorXd xin(n);
	Eigen::MatrixXd Pin(n, n);
	for (Eigen::Index i = 0; i < n; ++i)
	{
		xin[i] = x[in[size_t(i)]];
		for (Eigen::Index j = 0; j < n; ++j) Pin(i, j) = P(in[size_t(i)], in[size_t(j)]);
	}
	const auto cols = [](const Eigen::VectorXd& v, Eigen::Index at, Eigen::Index k)
	{ return Eigen::Map<const Eigen::Matrix2Xd>(v.data() + at, 2, k); };
	const Eigen::Matrix2Xd f0A = cols(xin, 3, A.founders), fB = cols(xin, cfB, m);
	Eigen::MatrixXd Jf;
	estimator::TLiveMergeSample s;
	s.step = step;
	s.y = Eigen::Map<const Eigen::VectorXd>(
	    models::mergeObjectFeatures(xin.head(3), f0A, xin.segment(cxiB, B.dim), fB, B.founders, &Jf)
	        .data(),
	    2 * m);
	Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * m, n);
	J.leftCols(Jf.cols()) = Jf;
	s.S = J * Pin * J.transpose();
	if (!vel) return s;
	Eigen::MatrixXd Jr;
	const Eigen::VectorXd r = models::rigidVelocityResidual(
	    xin.head<3>(), f0A, xin.segment<3>(cvA), xin.segment(cxiB, B.dim), fB.leftCols(B.founders),
	    xin.segment(cvA + 3, B.dim), &Jr);
	// Jr's columns: [xi_A | f0A | v_A | xi_B | B's founders | v_B] into the input's order.
	Eigen::MatrixXd Jv = Eigen::MatrixXd::Zero(r.size(), n);
	Jv.leftCols(3 + 2 * A.founders) = Jr.leftCols(3 + 2 * A.founders);
	Jv.middleCols(cvA, 3) = Jr.middleCols(3 + 2 * A.founders, 3);
	Jv.middleCols(cxiB, B.dim + 2 * B.founders) =
	    Jr.middleCols(6 + 2 * A.founders, B.dim + 2 * B.founders);
	Jv.middleCols(cvA + 3, B.dim) = Jr.rightCols(B.dim);
	const Eigen::MatrixXd R = Jv * Pin * Jv.transpose();
	s.vel_chi2 = r.dot(R.ldlt().solve(r));
	s.vel_dof = int(r.size());
	return s;
}

std::unique_ptr<CLiveMergeModule> makeLiveMergeModule(TFilterAccess& a)
{
	// The live merge belongs to the routers that classify (their registry capability; a user
	// router outside the registry has none).
	const auto& reg = estimator::routers();
	const std::string router = a.router().name();
	if (!reg.has(router) || !reg.caps(router).classifies) return nullptr;
	auto detector =
	    estimator::makeLiveMergeDetector(a.options().classify, a.motion().objectCentric());
	if (!detector) return nullptr;  // classify_merge_live off
	return std::make_unique<CLiveMergeModule>(std::move(detector));
}

void CLiveMergeModule::afterCommit(TFilterAccess& a)
{
	const int step = a.step();
	estimator::IMeasurementRouter& router = a.router();
	const estimator::CPaddedLayout& layout = a.layout();
	std::set<int32_t> seen;
	for (const estimator::TRoutedReading& r : a.routed().readings)
		if (r.route == estimator::Route::ObjectTimeT && r.object >= 0) seen.insert(r.object);
	const Eigen::VectorXd x = a.mean();
	const std::vector<TLive> live =
	    liveObjects(layout, router.registry(), x, step, a.motion().objectCentric(), seen);
	const ekf::CSquareBuffer::ConstView P = a.covBuffer().view();
	std::vector<std::pair<int32_t, int32_t>> merges;  // (from, into)
	std::set<int32_t> busy;
	for (size_t i = 0; i < live.size(); ++i)
		for (size_t j = i + 1; j < live.size(); ++j)
		{
			// Into the rigid one (two translation-only objects are never merged), else the
			// older (smaller ID).
			if (live[i].dim == 2 && live[j].dim == 2) continue;
			const bool iInto = live[i].dim == 3 && (live[j].dim == 2 || live[i].obj < live[j].obj);
			const TLive& A = iInto ? live[i] : live[j];
			const TLive& B = iInto ? live[j] : live[i];
			if ((A.p - B.p).norm() > a.options().classify.group_max_dist) continue;
			if (!router.allowsMerge(A.obj, B.obj)) continue;  // e.g. two boxes
			const estimator::TLiveMergeSample smp = liveSample(layout, x, P, A, B, step);
			const estimator::TLiveMergeStats st = m_detector->observe(A.obj, B.obj, smp);
			if (!st.rigid || busy.count(A.obj) || busy.count(B.obj)) continue;
			merges.emplace_back(B.obj, A.obj);
			busy.insert(A.obj);
			busy.insert(B.obj);
		}
	m_detector->prune(step, 2 * m_detector->window() + 2);
	for (const auto& [from, into] : merges)
		if (mergeObjects(a, from, into)) ++a.report().objects_merged_live;
}
}  // namespace dynslam::ekf
