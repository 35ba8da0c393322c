// Seed 004's matrix uniforms (`uniform mat4 MV; uniform mat4 MVP; uniform mat3 NM;`, set with
// glUniformMatrix*fv from glm) as one block, filled on the CPU in float as glm computes them.
// MVP's depth row is mapped to wgpu's 0..1 (x, y and w are the course's).
layout(set = 0, binding = 0) uniform Matrices {
    mat4 MV;  // ModelView
    mat4 MVP; // Projection * ModelView
    mat3 NM;  // Normal Matrix: transpose(inverse(mat3(MV)))
};
