#pragma once
// Small synthetic sessions of both studies whose tables can be worked out by hand (the expected
// numbers are derived in the comments of test_analysis.cpp and test_study_analyze_cli.cpp).
#include <string>
#include <vector>

#include "clients/study/session.hpp"

namespace thx::study::fixtures {

inline SessionHeader header(Study study, const std::string& participant, std::uint64_t seed) {
  SessionHeader h;
  h.study = study;
  h.participant = participant;
  h.seed = seed;
  h.software = "texhaptics 0.1 test";
  if (study == Study::Identification) {
    h.surfaces = {{"bricks_a", "bricks"}, {"bricks_b", "bricks"}, {"metal_a", "metal"},
                  {"metal_b", "metal"},   {"wood_a", "wood"},     {"wood_b", "wood"}};
  } else {
    h.surfaces = {{"wood_1", "wood"}, {"stone_1", "stone"}, {"tile", "ceramic"}, {"metal", "metal"}};
  }
  return h;
}

// One Study 1 trial: `off` names the cue removed ("" for none).
inline TrialRow idTrial(int trial, const std::string& surface, const std::string& off, const std::string& answer,
                        double time_s) {
  TrialRow r;
  r.trial = trial;
  r.surface = surface;
  r.cues = {off != "sound", off != "ball", off != "pen"};
  r.answer = answer;
  r.correct = answer == surface;
  r.time_s = time_s;
  r.setRating(Rating::Ease, 5 + trial % 3);
  if (r.cues.sound) r.setRating(Rating::UseSound, 3), r.setRating(Rating::AccSound, 7);
  if (r.cues.ball) r.setRating(Rating::UseBall, 2), r.setRating(Rating::AccBall, 4);
  if (r.cues.pen) r.setRating(Rating::UsePen, 5), r.setRating(Rating::AccPen, 9);
  return r;
}

// One Study 2 rating row: realism 8 for relief and 6 for normal, overall as given.
inline TrialRow rated(int trial, const std::string& surface, Representation rep, int overall) {
  TrialRow r;
  r.trial = trial;
  r.surface = surface;
  r.representation = rep;
  r.setRating(Rating::Realism, rep == Representation::Relief ? 8 : 6);
  r.setRating(Rating::MatchPhysics, 5 + trial % 2);
  r.setRating(Rating::MatchSound, 4 + trial % 3);
  r.setRating(Rating::MatchHaptics, overall > 5 ? 7 : 5);
  r.setRating(Rating::Overall, overall);
  return r;
}

// Study 1: two participants, six trials each (three with all cues, then no sound, ball, pen).
inline std::vector<Session> identificationSessions() {
  Session p1{"p1_id.csv", header(Study::Identification, "P1", 11), {}};
  p1.trials = {idTrial(1, "bricks_a", "", "bricks_a", 10),   idTrial(2, "wood_a", "", "wood_a", 20),
               idTrial(3, "metal_a", "", "metal_b", 30),     idTrial(4, "bricks_b", "sound", "wood_a", 40),
               idTrial(5, "wood_b", "ball", "wood_b", 12),   idTrial(6, "metal_b", "pen", "metal_b", 18)};
  Session p2{"p2_id.csv", header(Study::Identification, "P2", 12), {}};
  p2.trials = {idTrial(1, "metal_b", "", "metal_b", 14),     idTrial(2, "bricks_a", "", "bricks_a", 16),
               idTrial(3, "wood_b", "", "wood_a", 25),       idTrial(4, "wood_a", "sound", "wood_a", 30),
               idTrial(5, "metal_a", "ball", "bricks_a", 9), idTrial(6, "bricks_b", "pen", "bricks_b", 22)};
  return {p1, p2};
}

// Study 2: three participants with two relief and two normal surfaces each, and P4 who saw
// only normal maps.
inline std::vector<Session> ratingSessions() {
  using R = Representation;
  Session p1{"p1_rv.csv", header(Study::ReliefVsNormal, "P1", 21), {}};
  p1.trials = {rated(1, "wood_1", R::Relief, 8), rated(2, "stone_1", R::Relief, 6), rated(3, "tile", R::Normal, 5),
               rated(4, "metal", R::Normal, 5)};
  Session p2{"p2_rv.csv", header(Study::ReliefVsNormal, "P2", 22), {}};
  p2.trials = {rated(1, "tile", R::Relief, 9), rated(2, "wood_1", R::Normal, 6), rated(3, "metal", R::Relief, 7),
               rated(4, "stone_1", R::Normal, 4)};
  Session p3{"p3_rv.csv", header(Study::ReliefVsNormal, "P3", 23), {}};
  p3.trials = {rated(1, "stone_1", R::Normal, 5), rated(2, "wood_1", R::Relief, 6), rated(3, "metal", R::Normal, 3),
               rated(4, "tile", R::Relief, 6)};
  Session p4{"p4_rv.csv", header(Study::ReliefVsNormal, "P4", 24), {}};
  p4.trials = {rated(1, "wood_1", R::Normal, 5), rated(2, "stone_1", R::Normal, 5), rated(3, "tile", R::Normal, 5),
               rated(4, "metal", R::Normal, 5)};
  return {p1, p2, p3, p4};
}

}  // namespace thx::study::fixtures
