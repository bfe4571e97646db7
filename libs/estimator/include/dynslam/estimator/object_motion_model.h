#pragma once
/** @file object_motion_model.h
 * Seam 2 of the estimator core (doc/architecture.md): what happens to moving objects between
 * and within steps, as pseudo-measurements 0 = r(poses) + n, n ~ N(0, R), on an object's
 * poses. The EKF applies one as an update of the poses' state entries
 * (ekf::pseudoMeasurementUpdate); the framework adds the same object as a residual term
 * (framework::CMotionModelTerm). Implementations: "none" (the paper's default: objects only
 * follow their features) and the paper's smoothing (Alg. 6). */
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace dynslam::estimator
{
/** One pseudo-measurement on the poses of object `object` at `steps` (each of `dim`
 * entries), with noise covariance R. */
struct TPseudoMeasurement
{
	int32_t object = -1;
	std::vector<int> steps;
	int dim = 0;
	Eigen::MatrixXd R;
};

class IObjectMotionModel
{
public:
	virtual ~IObjectMotionModel() = default;
	virtual std::string name() const = 0;
	/** The fewest poses per object the model needs kept in the state (K). */
	virtual int posesNeeded() const = 0;
	/** This step's pseudo-measurements on object `object`, whose poses in the state are at
	 * `poseSteps` (ascending), each of `dim` entries. */
	virtual std::vector<TPseudoMeasurement> select(int32_t object, int step,
	                                               const std::vector<int>& poseSteps,
	                                               int dim) const = 0;
	/** r at the poses (one vector per entry of m.steps) and, if J is given, J_r_pose for each. */
	virtual Eigen::VectorXd residual(const TPseudoMeasurement& m,
	                                 const std::vector<Eigen::VectorXd>& poses,
	                                 std::vector<Eigen::MatrixXd>* J) const = 0;

	// --- Object-centric models (issue 13). The defaults are the paper's formulation: no
	// object state beyond the poses, objects predicted by nothing, their sightings define
	// time-t features (Alg. 3) and poses (Alg. 4). A model with velocityDim() > 0 gives each
	// object, once it has its first pose, a velocity block (BlockKind::ObjectVelocity); then the
	// object's pose and velocity are predicted every step (predict) and every sighting of one of
	// its features is a measurement update of ego, pose and body-frame features together.
	/** Entries of the velocity block of an object with a pose of poseDim entries (0: none). */
	virtual int velocityDim(int /*poseDim*/) const { return 0; }
	/** Capability: an object-centric model (a velocity block for a pose of 2 or 3 entries). */
	bool objectCentric() const { return velocityDim(3) > 0 || velocityDim(2) > 0; }
	/** Capability: the model acts on an object's poses once they are in the state (pseudo-
	 * measurements, velocity blocks): the step commits the new poses before it. False for the
	 * paper's model without smoothing (CNoObjectMotion). */
	virtual bool actsOnNewPoses() const { return true; }
	/** One step's transition of s = [pose; velocity]: returns s', J_out_s and Q. */
	virtual Eigen::VectorXd predict(const Eigen::VectorXd& s, Eigen::MatrixXd* J_out_s,
	                                Eigen::MatrixXd* Q) const;
	/** The velocity of an object from its first pose xi, `steps` steps after its time 0:
	 * v = f(xi), J_v_xi, and the prior covariance added to it (the initialisation noise). */
	virtual Eigen::VectorXd initialVelocity(const Eigen::VectorXd& xi, int steps,
	                                        Eigen::MatrixXd* J_v_xi, Eigen::MatrixXd* Sigma) const;
	/** Chi-square threshold (2 dof) of the gate on object readings (infinity: no gate). */
	virtual double readingGate() const;
	/** Fallback of a lost object: called at every step with readings of an object that has a
	 * velocity; allGatedOut = the gate rejected all of them. True: the object is lost and its
	 * motion state leaves the filter now (the model has then forgotten its per-object state). */
	virtual bool reportGating(int32_t /*object*/, bool /*allGatedOut*/) { return false; }
	/** Forgets all per-object state (the filter's reset). */
	virtual void resetObjectState() {}

	// --- Multiple-model objects (issue 28, models/mode_mixture.h). modeCount() > 0: the
	// object-centric prediction is the moment-matched mixture of the modes' predictions, the
	// mode probabilities updated by the object's readings (the EKF and Alg. 1,
	// estimator::CObjectModes). All modes share the velocity block of velocityDim().
	/** Number of modes (0: a single model, predict()). */
	virtual int modeCount() const { return 0; }
	virtual std::string modeName(int /*mode*/) const { return name(); }
	/** Mode j's transition of s = [pose; velocity]: s', J_out_s and Q (like predict()). */
	virtual Eigen::VectorXd predictMode(int /*mode*/, const Eigen::VectorXd& s,
	                                    Eigen::MatrixXd* J_out_s, Eigen::MatrixXd* Q) const
	{
		return predict(s, J_out_s, Q);
	}
	/** Markov switching Pi (modeCount() x modeCount(), rows: from, columns: to). */
	virtual Eigen::MatrixXd modeTransition() const { return Eigen::MatrixXd(); }
	/** Mode probabilities of an object when its velocity enters the state. */
	virtual Eigen::VectorXd initialModeProbabilities() const { return Eigen::VectorXd(); }
};

/** No motion model (the paper's default). */
class CNoObjectMotion : public IObjectMotionModel
{
public:
	std::string name() const override { return "none"; }
	int posesNeeded() const override { return 1; }
	bool actsOnNewPoses() const override { return false; }
	std::vector<TPseudoMeasurement> select(int32_t, int, const std::vector<int>&,
	                                       int) const override
	{
		return {};
	}
	Eigen::VectorXd residual(const TPseudoMeasurement&, const std::vector<Eigen::VectorXd>&,
	                         std::vector<Eigen::MatrixXd>*) const override;
};

/** The paper's smoothing (Alg. 6): s(xi_{t-2}, xi_{t-1}, xi_t) = 0 + n_s, n_s ~ N(0, Sigma_s),
 * on the poses of three consecutive steps ending now (models/smoothing.h). */
class CPaperSmoothing : public IObjectMotionModel
{
public:
	/** Sigma_s: 3x3 (its top-left 2x2 is used for translation-only poses). */
	explicit CPaperSmoothing(const Eigen::Matrix3d& Sigma_s) : m_Sigma_s(Sigma_s) {}
	std::string name() const override { return "paper_smoothing"; }
	int posesNeeded() const override { return 3; }
	std::vector<TPseudoMeasurement> select(int32_t object, int step,
	                                       const std::vector<int>& poseSteps,
	                                       int dim) const override;
	Eigen::VectorXd residual(const TPseudoMeasurement& m, const std::vector<Eigen::VectorXd>& poses,
	                         std::vector<Eigen::MatrixXd>* J) const override;

private:
	Eigen::Matrix3d m_Sigma_s;
};
}  // namespace dynslam::estimator
