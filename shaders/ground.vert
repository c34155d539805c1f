#version 330 core
// The ground quad: a unit square in x-z, placed on the plane by uModel. vGrid is the position
// in the plane's own coordinates, so the grid follows a tilted plane too.
layout(location = 0) in vec3 aPosition;

uniform mat4 uViewProjection;
uniform mat4 uModel;
uniform vec3 uPlaneOffset;  // the quad centre in plane coordinates (x, unused, z)
uniform float uExtent;      // half the quad's side, m

out vec2 vGrid;

void main() {
  vGrid = uPlaneOffset.xz + aPosition.xz * uExtent;
  gl_Position = uViewProjection * uModel * vec4(aPosition, 1.0);
}
