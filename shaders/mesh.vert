#version 330 core
// Meshes: position and normal to world space; the normal with the inverse transpose so that
// non-uniform scale (boxes of any size from one unit cube) keeps it perpendicular.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uViewProjection;
uniform mat4 uModel;

out vec3 vNormal;

void main() {
  vNormal = transpose(inverse(mat3(uModel))) * aNormal;
  gl_Position = uViewProjection * uModel * vec4(aPosition, 1.0);
}
