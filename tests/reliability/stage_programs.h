// The stage programs the reliability tests run, by their paths in the build (the target's
// STAGEn_EXE definitions): all seven, those that read meshes (stage 1 has no triangles), and those
// with area emitters (stage 4 on).
#pragma once

namespace rt::testing {

inline constexpr const char* kPrograms[] = {STAGE1_EXE, STAGE2_EXE, STAGE3_EXE, STAGE4_EXE,
                                            STAGE5_EXE, STAGE6_EXE, STAGE7_EXE};
inline constexpr const char* kMeshPrograms[] = {STAGE2_EXE, STAGE3_EXE, STAGE4_EXE, STAGE5_EXE, STAGE6_EXE, STAGE7_EXE};
inline constexpr const char* kEmitterPrograms[] = {STAGE4_EXE, STAGE5_EXE, STAGE6_EXE, STAGE7_EXE};

}  // namespace rt::testing
