#pragma once
// Analytic answers for the standard scenes, derived from the scene itself, so that the
// sweep scores both engines against physics rather than against each other.

#include <string>

#include "sim/scene.h"

namespace polysim::sim {

/// A body dropped alone from rest, unrotated relative to the flat top of the static bodies
/// below it, with no air and a rigid ground. Heights are of the body frame's origin along
/// -gravity (m).
struct DropReference {
  double gap = 0.0;               // m, from the body's lowest vertex down to the highest static vertex
  double firstContactTime = 0.0;  // s, sqrt(2 gap / g)
  double restHeight = 0.0;        // m, where it rests: its start height less the gap
  double bounceApex = 0.0;        // m, the first rebound's apex: rest height + e^2 gap (e: the pair's restitution)
};

/// Throws std::invalid_argument naming the scene and body when the scene is not such a
/// drop (the body moves at the start, another body moves, or it is not above every
/// static vertex).
DropReference dropReference(const Scene& scene, const std::string& body);

/// How far (m) a body starting at rest on a static ramp slides down it in `duration`
/// seconds under Coulomb friction: g (sin θ - mu cos θ) duration^2 / 2, or 0 when
/// tan θ <= mu. θ is the ramp's tilt (the angle between its frame's z axis and -gravity),
/// mu the pair's friction sqrt(mu_body mu_ramp). Throws std::invalid_argument naming the
/// scene and body when either is missing or the body moves at the start.
double inclineSlideDistance(const Scene& scene, const std::string& body, const std::string& ramp, double duration);

}  // namespace polysim::sim
