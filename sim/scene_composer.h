#pragma once
// Composes one MJCF scene from the scenario: world piece + robot piece + generated pieces
// (obstacles, terrain), under one <compiler>/<option>/<visual> header.
#include <string>
#include <vector>

#include "scenario/scenario.h"

namespace viqu::sim {

// Reads an MJCF piece (a file whose root is <mujoco>) and returns its inner elements with every
// file="..." attribute made absolute (relative to the piece's folder), comments blanked and line
// breaks kept; `first_line` (when given) gets the file's line on which the returned text starts.
// Throws viqu::InputError naming the file if it cannot be read, has no <mujoco> root, or holds
// <compiler>/<include>.
std::string InlineMjcfPiece(const std::string& path, int* first_line = nullptr);

// The header values that the composer writes.
struct SceneHeader {
  double timestep_s = 0.001;  // physics step (s)
  int offscreen_width = 640;  // off-screen buffer size (px)
  int offscreen_height = 480;
  // Contact model. Small feet creep under MuJoCo's soft pyramidal cones; an elliptic cone with a
  // high impedance ratio and a few no-slip iterations keep stance feet planted.
  std::string cone = "elliptic";
  double impratio = 10;
  int noslip_iterations = 3;
};

// The whole scene as MJCF text. `generated` are inner-MJCF pieces (e.g. from ObstaclesXml).
std::string ComposeSceneXml(const Scenario& s, const SceneHeader& header,
                            const std::vector<std::string>& generated);

// "FILE:LINE" of the world or robot file that line `line` (1-based) of a scene composed by
// ComposeSceneXml came from; "" for the header and the generated pieces.
std::string SourceOfComposedLine(const std::string& xml, int line);

}  // namespace viqu::sim
