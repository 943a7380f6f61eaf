#pragma once
// Perceptual colour maps (sRGB, components in [0, 1]) sampled by a value in [0, 1].
namespace fluidbed::render {

struct Rgb {
  float r = 0.0f, g = 0.0f, b = 0.0f;
};

enum class ColourMap {
  viridis,  // particles: dark blue (low) to yellow (high)
  inferno,  // gas arrows coloured by speed: black to pale yellow
};

// The map's colour at t (clamped to [0, 1]; NaN gives the low end), linear between the 256 entries.
Rgb colour_at(ColourMap map, double t);

}  // namespace fluidbed::render
