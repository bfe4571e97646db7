#include <dynslam/core/kernels.h>
#include <dynslam/estimator/compressed_state.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace dynslam::estimator
{
namespace
{
/** Storage offsets (within the blocks' own storage, in order) of the non-Compressed blocks and
 * of the Compressed blocks (sorted by their pair index). */
void splitPassive(const std::vector<TBlock>& blocks, std::vector<int>& final_pos,
                  std::vector<int>& comp_pos)
{
	std::vector<std::pair<int, int>> comp;  // (pair index, offset)
	int off = 0;
	for (const TBlock& b : blocks)
	{
		const int w = 2 * b.slots();
		if (b.kind == BlockKind::Compressed)
			comp.push_back({b.feature, off});
		else
			for (int i = 0; i < w; ++i) final_pos.push_back(off + i);
		off += w;
	}
	std::sort(comp.begin(), comp.end());
	for (const auto& [j, o] : comp)
	{
		comp_pos.push_back(o);
		comp_pos.push_back(o + 1);
	}
}
/** Writes (xo, Po, out) to (x, P, layout) with the blocks in creation order (TBlock::seq,
 * the full EKF's storage order). */
void restoreCreationOrder(const CPaddedLayout& out, const Eigen::VectorXd& xo,
                          const ekf::RowMatrixXd& Po, Eigen::VectorXd& x, ekf::RowMatrixXd& P,
                          CPaddedLayout& layout)
{
	std::vector<size_t> order(out.size());
	for (size_t b = 0; b < order.size(); ++b) order[b] = b;
	std::stable_sort(order.begin(), order.end(),
	                 [&](size_t a, size_t b) { return out[a].seq < out[b].seq; });
	CPaddedLayout sorted;
	std::vector<int> perm{0, 1, 2};
	for (const size_t b : order)
	{
		sorted.appendNumbered(out[b]);
		for (int i = 0; i < 2 * out[b].slots(); ++i) perm.push_back(out.first(b) + i);
	}
	x = xo(perm);
	P = Po(perm, perm);
	layout = std::move(sorted);
}
/** One level of the global update: xB = x + cross^T beta, CB = G cross,
 * BB = P + cross^T Q cross, symmetrized (a dispatched kernel, dynslam/core/kernels.h). */
void expandLevel(const TPassiveLevel& lv, const Eigen::MatrixXd& G, const Eigen::MatrixXd& Q,
                 const Eigen::VectorXd& beta, Eigen::VectorXd& xB, Eigen::MatrixXd& CB,
                 Eigen::MatrixXd& BB)
{
	const Eigen::Index p = lv.P.rows(), m0 = lv.m0;
	if (lv.x.size() != p || lv.P.cols() != p || lv.cross.rows() != m0 || lv.cross.cols() != p ||
	    Q.rows() != m0 || Q.cols() != m0 || G.cols() != m0 || beta.size() != m0)
		throw std::logic_error("expandState: level " + std::to_string(lv.level) +
		                       " has inconsistent sizes");
	xB.resize(p);
	CB.resize(G.rows(), p);
	BB.resize(p, p);
	kernels::TExpandLevelArgs k;
	k.G = G.data();
	k.nf = G.rows();
	k.m0 = m0;
	k.Q = Q.data();
	k.beta = beta.data();
	k.cross = lv.cross.data();
	k.p = p;
	k.P = lv.P.data();
	k.x = lv.x.data();
	k.xB = xB.data();
	k.CB = CB.data();
	k.BB = BB.data();
	kernels::expandLevel(k);
}
}  // namespace

TPassiveLevel compressState(const Eigen::Ref<const Eigen::VectorXd>& x,
                            const Eigen::Ref<const ekf::RowMatrixXd>& P, CPaddedLayout& layout,
                            const std::vector<bool>& passive, int level, Eigen::VectorXd& xo,
                            ekf::RowMatrixXd& Po)
{
	if (passive.size() != layout.size() || x.size() != layout.storageDim() ||
	    P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("compressState: state, layout and flags do not match");
	TPassiveLevel lv;
	lv.level = level;
	std::vector<int> pass;
	for (size_t b = 0; b < layout.size(); ++b)
	{
		if (layout[b].kind == BlockKind::Compressed && !passive[b])
			throw std::logic_error("compressState: the previous level's entries must be passive");
		if (!passive[b]) continue;
		lv.blocks.push_back(layout[b]);
		for (int i = 0; i < 2 * layout[b].slots(); ++i) pass.push_back(layout.first(b) + i);
	}
	const std::vector<int> keep = layout.keptStorage(passive);
	const Eigen::Index m0 = Eigen::Index(keep.size()), s = m0 + m0 % 2;
	lv.m0 = int(m0);
	lv.x = x(pass);
	lv.P = P(pass, pass);
	lv.cross = P(keep, pass);

	xo = Eigen::VectorXd::Zero(m0 + s);
	xo.head(m0) = x(keep);
	Po = ekf::RowMatrixXd::Zero(m0 + s, m0 + s);
	Po.topLeftCorner(m0, m0) = P(keep, keep);
	Po.block(0, m0, m0, m0).setIdentity();
	Po.block(m0, 0, m0, m0).setIdentity();
	layout.removeBlocks(passive);
	for (Eigen::Index j = 0; j < s / 2; ++j)
	{
		TBlock c;
		c.kind = BlockKind::Compressed;
		c.object = level;
		c.feature = int(j);
		c.dim = 2;
		layout.append(c);
	}
	return lv;
}

void expandState(Eigen::VectorXd& x, ekf::RowMatrixXd& P, CPaddedLayout& layout,
                 std::vector<TPassiveLevel>& levels)
{
	if (levels.empty()) return;
	if (x.size() != layout.storageDim() || P.rows() != x.size() || P.cols() != x.size())
		throw std::invalid_argument("expandState: state and layout do not match");
	// The last level's Compressed entries in the state, in pair order.
	std::vector<bool> isC(layout.size(), false);
	for (size_t b = 0; b < layout.size(); ++b)
		if (layout[b].kind == BlockKind::Compressed)
		{
			if (layout[b].object != levels.back().level)
				throw std::logic_error("expandState: compressed entries of another level");
			isC[b] = true;
		}
	std::vector<std::pair<int, int>> comp;
	for (size_t b = 0; b < layout.size(); ++b)
		if (isC[b]) comp.push_back({layout[b].feature, layout.first(b)});
	std::sort(comp.begin(), comp.end());
	std::vector<int> sur;
	for (const auto& [j, o] : comp) sur.insert(sur.end(), {o, o + 1});
	const std::vector<int> act = layout.keptStorage(isC);
	CPaddedLayout out;
	for (size_t b = 0; b < layout.size(); ++b)
		if (!isC[b]) out.appendNumbered(layout[b]);

	Eigen::Index N = Eigen::Index(act.size());
	for (const auto& lv : levels)
		for (const TBlock& b : lv.blocks)
			if (b.kind != BlockKind::Compressed) N += 2 * b.slots();
	Eigen::VectorXd xo(N);
	ekf::RowMatrixXd Po(N, N);
	Eigen::Index nf = Eigen::Index(act.size());
	xo.head(nf) = x(act);
	Po.topLeftCorner(nf, nf) = P(act, act);

	// G = cov(entries so far, C), Q = cov(C, C), beta = x_C of the level being unwound.
	const int m0 = levels.back().m0;
	if (int(sur.size()) < m0) throw std::logic_error("expandState: too few compressed entries");
	sur.resize(size_t(m0));
	Eigen::MatrixXd G = P(act, sur);
	Eigen::MatrixXd Q = P(sur, sur);
	Eigen::VectorXd beta = x(sur);
	for (size_t l = levels.size(); l-- > 0;)
	{
		const TPassiveLevel& lv = levels[l];
		if (G.cols() != lv.m0 || G.rows() != nf)
			throw std::logic_error("expandState: level " + std::to_string(lv.level) +
			                       " does not match the state");
		Eigen::VectorXd xB;
		Eigen::MatrixXd CB, BB;
		expandLevel(lv, G, Q, beta, xB, CB, BB);
		std::vector<int> F, S;
		splitPassive(lv.blocks, F, S);
		const Eigen::Index nF = Eigen::Index(F.size());
		xo.segment(nf, nF) = xB(F);
		Po.block(0, nf, nf, nF) = CB(Eigen::all, F);
		Po.block(nf, 0, nF, nf) = CB(Eigen::all, F).transpose();
		Po.block(nf, nf, nF, nF) = BB(F, F);
		for (const TBlock& b : lv.blocks)
			if (b.kind != BlockKind::Compressed) out.appendNumbered(b);
		if (l == 0)
		{
			if (!S.empty()) throw std::logic_error("expandState: the first level holds C entries");
			break;
		}
		const int m0p = levels[l - 1].m0;
		if (int(S.size()) < m0p) throw std::logic_error("expandState: level entries missing");
		S.resize(size_t(m0p));
		Eigen::MatrixXd Gn(nf + nF, m0p);
		Gn.topRows(nf) = CB(Eigen::all, S);
		Gn.bottomRows(nF) = BB(F, S);
		G = std::move(Gn);
		Q = BB(S, S);
		beta = xB(S);
		nf += nF;
	}
	restoreCreationOrder(out, xo, Po, x, P, layout);
	levels.clear();
}
}  // namespace dynslam::estimator
