#pragma once
// `polysim compare`: a scene run in polysim and in ODE with the same settings, their
// summaries side by side, and where they disagree.

#include <nlohmann/json.hpp>

#include "sim/ode_world.h"
#include "sim/run.h"
#include "sim/scene.h"

namespace polysim::sim {

/// Runs the scene in ODE and returns SPEC.md's summary plus "engine": "ode" and the
/// "settings" used (stepper, iterations, erp, cfm). max_penetration is the deepest
/// contact depth ODE reported at any step; first_contact_time the start of the first step
/// whose collision pass found a contact.
nlohmann::ordered_json runOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings = {});

/// Both summaries and their comparison:
/// - per body: position and orientation differences, at_rest, drift (horizontal
///   displacement from the start, m) and height change (m), each [polysim, ode];
/// - first contact time, maximum penetration, final energy, wall time, [polysim, ode];
/// - contacts: at every step's end where polysim has contacts, ODE is asked about the same
///   poses (see kOdePressFactor) and the largest disagreements are reported with where
///   they happened (ContactAgreement);
/// - findings: plain sentences for what went wrong in either engine (overlap beyond ten
///   tolerances, energy gained, a body below every static body, a body drifting more than
///   1 cm, at-rest states that differ), so that known ODE failures are shown, not hidden.
/// With options.logDirectory, both runs' step logs go there: polysim.jsonl (with each
/// step's contacts) and ode.jsonl, for `polysim view`.
nlohmann::ordered_json compareWithOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings = {});

}  // namespace polysim::sim
