#version 330 core
// One directional light plus ambient (engine::shade is the same formula on the CPU).
in vec3 vNormal;

uniform vec3 uColor;
uniform float uAlpha;  // 1 opaque; below 1 for the method overlay's translucent runs
uniform vec3 uTowardsLight;
uniform float uAmbient;
uniform float uDiffuse;

out vec4 fragColor;

void main() {
  vec3 n = normalize(vNormal);
  float light = uAmbient + uDiffuse * max(dot(n, uTowardsLight), 0.0);
  fragColor = vec4(uColor * light, uAlpha);
}
