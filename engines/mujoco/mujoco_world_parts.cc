#include "engines/mujoco/mujoco_world_parts.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <stdexcept>

namespace rockbench::mujoco {

std::string ContactAttributes(const ContactParams& c) {
  return "solref=\"" + Num(c.solref[0]) + " " + Num(c.solref[1]) + "\" solimp=\"" +
         Num(c.solimp[0]) + " " + Num(c.solimp[1]) + " " + Num(c.solimp[2]) + " " +
         Num(c.solimp[3]) + " " + Num(c.solimp[4]) + "\"";
}

std::string OptionMjcf(const EngineInput& in, const MujocoSettings& s, const std::string& gravity) {
  return "  <option timestep=\"" + Num(in.time_step_s) + "\" gravity=\"" + gravity +
         "\" integrator=\"" + MjcfIntegrator(s.integrator) + "\" solver=\"" + MjcfSolver(s.solver) +
         "\" iterations=\"" + std::to_string(s.iterations) + "\" tolerance=\"" + Num(s.tolerance) +
         "\" cone=\"" + std::string(ConeName(s.cone)) + "\" impratio=\"" + Num(s.impratio) +
         "\" noslip_iterations=\"" + std::to_string(s.noslip_iterations) +
         "\" noslip_tolerance=\"" + Num(s.noslip_tolerance) + "\"/>\n";
}

std::string GeomDefaultMjcf(const MujocoSettings& s, const ContactParams& c) {
  return "    <geom condim=\"3\" friction=\"" + Num(s.friction) +
         " 0.005 0.0001\" margin=\"0\" gap=\"0\" " + ContactAttributes(c) + "/>\n";
}

std::string SceneFrictionPairMjcf(const std::string& lower_body, const std::string& upper_body,
                                  const std::string& lower_geom, const std::string& upper_geom,
                                  double mu, const ContactParams& c) {
  return "    <exclude body1=\"" + lower_body + "\" body2=\"" + upper_body + "\"/>\n" +
         "    <pair geom1=\"" + lower_geom + "\" geom2=\"" + upper_geom + "\" condim=\"" +
         (mu > 0.0 ? "3" : "1") + "\" friction=\"" + Num(mu) + " " + Num(mu) +
         " 0.005 0.0001 0.0001\" " + ContactAttributes(c) + " margin=\"0\" gap=\"0\"/>\n";
}

MujocoSim::MujocoSim(const std::string& xml) {
  m_ = CompileMjcf(xml);
  d_ = mj_makeData(m_);
  if (!d_) {
    mj_deleteModel(m_);
    throw std::runtime_error("mujoco: mj_makeData failed");
  }
}

MujocoSim::~MujocoSim() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

bool MujocoSim::Step() {
  if (blown_up_) return false;
  const double t_before = d_->time;
  mj_step(m_, d_);
  // mj_step detects the contacts at the state before the step.
  max_contacts_ = std::max(max_contacts_, d_->ncon);
  max_iterations_ = std::max(max_iterations_, d_->solver_iter);
  // MuJoCo resets the simulation (time back to 0) when it meets a bad number in qpos, qvel or
  // qacc: that is the end of the run.
  if (d_->warning[mjWARN_BADQPOS].number > 0 || d_->warning[mjWARN_BADQVEL].number > 0 ||
      d_->warning[mjWARN_BADQACC].number > 0 || !(d_->time > t_before)) {
    blown_up_ = true;
  }
  return true;
}

nlohmann::json MujocoSim::Diagnostics() const {
  nlohmann::json j;
  j["contact_buffer_full"] = d_->warning[mjWARN_CONTACTFULL].number;
  j["constraint_buffer_full"] = d_->warning[mjWARN_CNSTRFULL].number;
  j["bad_qpos"] = d_->warning[mjWARN_BADQPOS].number;
  j["bad_qvel"] = d_->warning[mjWARN_BADQVEL].number;
  j["bad_qacc"] = d_->warning[mjWARN_BADQACC].number;
  j["max_contacts"] = max_contacts_;
  j["max_solver_iterations"] = max_iterations_;
  j["blown_up"] = blown_up_;
  return j;
}

nlohmann::json CommonSettings(const EngineInput& input, const MujocoSettings& s,
                              const mjModel_* m) {
  const ContactParams c = ContactParamsOf(s, input.time_step_s);
  nlohmann::json j;
  j["mujoco_version"] = mj_versionString();
  j["drive"] = "inertial";
  j["time_step_s"] = input.time_step_s;
  j["output_interval_s"] = input.run.output_interval_s;
  j["contact"] = std::string(ContactModelName(s.contact));
  j["solref"] = {c.solref[0], c.solref[1]};
  j["solimp"] = {c.solimp[0], c.solimp[1], c.solimp[2], c.solimp[3], c.solimp[4]};
  if (s.contact == ContactModel::kStiff) {
    j["stiff_timeconst_steps"] = s.stiff_timeconst_steps;
    j["stiff_dampratio"] = s.stiff_dampratio;
  }
  j["solver"] = std::string(SolverName(s.solver));
  j["iterations"] = s.iterations;
  j["tolerance"] = s.tolerance;
  j["integrator"] = std::string(IntegratorName(s.integrator));
  j["cone"] = std::string(ConeName(s.cone));
  j["impratio"] = s.impratio;
  j["friction"] = s.friction;
  j["noslip_iterations"] = s.noslip_iterations;
  j["noslip_tolerance"] = s.noslip_tolerance;
  j["margin_m"] = 0.0;
  j["refsafe"] = (m->opt.disableflags & mjDSBL_REFSAFE) == 0;
  j["warmstart"] = (m->opt.disableflags & mjDSBL_WARMSTART) == 0;
  return j;
}

}  // namespace rockbench::mujoco
