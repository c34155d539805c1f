#version 330 core
// The ground: a lit plane with grid lines one pixel wide at every multiple of uGridSpacing,
// antialiased by the screen-space rate of change of the grid coordinate.
in vec2 vGrid;

uniform vec3 uColor;
uniform vec3 uGridColor;
uniform float uGridSpacing;
uniform vec3 uNormal;
uniform vec3 uTowardsLight;
uniform float uAmbient;
uniform float uDiffuse;

out vec4 fragColor;

void main() {
  vec2 coord = vGrid / uGridSpacing;
  vec2 distanceInPixels = abs(fract(coord - 0.5) - 0.5) / max(fwidth(coord), vec2(1e-6));
  float onLine = 1.0 - min(min(distanceInPixels.x, distanceInPixels.y), 1.0);
  vec3 albedo = mix(uColor, uGridColor, onLine);
  float light = uAmbient + uDiffuse * max(dot(uNormal, uTowardsLight), 0.0);
  fragColor = vec4(albedo * light, 1.0);
}
