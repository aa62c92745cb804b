// Binding a mesh modelled around a BVH skeleton's rest pose (such as body_mesh.h grows) to that
// skeleton: SSD weights by equation 3.18 (ssd_weights.h) plus the joints and inverse bind matrices,
// as one SkinnedMesh that skins with the BVH's motion and exports to glTF (gltf_skin.h).
#pragma once

#include "performer/body_mesh.h"
#include "performer/body_weights.h"
#include "performer/skeleton.h"
#include "performer/skinned_mesh.h"
#include "performer/ssd_weights.h"
#include "performer/triangle_mesh.h"

namespace performer {

// Joints are the skeleton's joints in its order (end sites included, so a BVH motion row poses them
// through local_transforms and world_transforms as usual), translation = offset, identity rotation;
// inverse bind = inverse rest world transform. Weights go only to joints that are not end sites: an
// end site marks where a bone ends and has no motion of its own. Throws std::invalid_argument when
// the skeleton has no joint that is not an end site, or as ssd_weights does.
SkinnedMesh bind_to_skeleton(const Skeleton& skeleton, TriangleMesh mesh, const SsdWeightParams& params = {},
                             unsigned threads = 0);

// The same for a body grown around the skeleton (build_body_mesh), with the skeleton-aware weights
// of body_weights.h: each vertex moves with the bone it was grown from and that bone's neighbours
// along the skeleton only, so the skin holds together in motion. `skeleton` in its own units (the
// joints and inverse binds come out in the mesh's, body.output_scale times larger). Throws
// std::invalid_argument as body_ssd_weights does.
SkinnedMesh bind_body_to_skeleton(const Skeleton& skeleton, const BodyMesh& body, const BodyWeightParams& params = {},
                                  unsigned threads = 0);

}  // namespace performer
