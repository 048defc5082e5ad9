// reuse_cache.glsl - what a partial re-render reads of the frame-reuse state on the GPU (gpu/frame_reuse.h,
// docs/REUSE.md §4): the cached primary rays and hits of every path of the frame, the dirty list, and the padded
// moved bounds (FrameBlock::movedLo, movedHi), and the bounce cache with its links (FrameBlock::bounceFirst). Included
// after common.glsl and gpu/segment_cells.h.

// The caches are read through their uniform texel views (common.glsl HT_BINDING_REUSE_*, bound for every frame that
// keeps them: Renderer::Impl::bindReuseTexels): lavapipe turns each 32-bit component of a device-address load into a
// loop over the 8 lanes, while a texel fetch loads all lanes at once. Their writers reach them by device address.

// Word `k` of the marking pass's list (its header and entries, FrameReuseState::kListFirst).
uint reuse_list_word(uint k) { return UintRef(FRAME.refine).v[k]; }
// The padded moved bounds (FrameBlock::movedLo / movedHi), loaded once per invocation by load_moved_view(): the
// marking pass's tests read them for every segment.
vec3 gMovedLo = vec3(1.0f), gMovedHi = vec3(-1.0f);
void load_moved_view() {
  gMovedLo = FRAME.movedLo.xyz;
  gMovedHi = FRAME.movedHi.xyz;
}
vec3 moved_lo() { return gMovedLo; }
// Are the moved instances since the last frame known (FrameBlock::movedInstanceIds, set on a two-level BVH only)?
// If not, rays are traced whole.
bool moved_instances_known() { return FRAME.movedInstanceIds.x != 0xFFFFFFFFu; }
vec3 moved_hi() { return gMovedHi; }

// Word `w` of the segment masks (and what follows them, common.glsl accum_reach_word), through the marking pass's
// texel view of them.
uint reuse_mask_word(uint w) { return texelFetch(reuseMaskTexels, int(w / 4u))[w % 4u]; }

// The frame path of path `batchPath` of a batch of listed targets (entry (batchFirst + batchPath) / spp of the list).
uint listed_frame_path(uint batchPath) {
  uint spp = FRAME.dims.z;
  uint target = UintRef(FRAME.refine).v[FRAME.refineInfo.y + (pc.batchFirst + batchPath) / spp];
  return target * spp + (pc.batchFirst + batchPath) % spp;
}

uvec4 cached_primary_hit(uint path) { return texelFetch(reusePrimaryHitTexels, int(path)); }
HtHit cached_primary_ht_hit(uint path) { return hit_of_bits(cached_primary_hit(path)); }
HtRay cached_primary_ray(uint path) {
  vec4 a = texelFetch(reusePrimaryRayTexels, int(2u * path)), b = texelFetch(reusePrimaryRayTexels, int(2u * path + 1u));
  return HtRay(a.xyz, a.w, b.xyz, b.w);
}

// Does the segment of `ray` to `hit` (its cached hit's bits; a miss: to tmax) meet the padded moved bounds? If not,
// that hit is still the ray's hit: every triangle of the moved node lies inside those bounds, every other triangle
// is unchanged, and the closest hit is the order-free one.
bool segment_to_hit_meets_moved(HtRay ray, uvec4 hit) {
  float tEnd = hit.y != HT_MISS ? uintBitsToFloat(hit.x) : ray.tmax;
  return ht_segment_meets_box(ray.origin, ray.dir, ray.tmin, tEnd, moved_lo(), moved_hi());
}
// ... for the cached primary segment of frame path `path`; `hit`: its cached hit (cached_primary_hit).
bool cached_primary_meets_moved(uint path, uvec4 hit) { return segment_to_hit_meets_moved(cached_primary_ray(path), hit); }

// The bounce cache (FrameReuseState::secondaryRegion) of FRAME.moved.w entries, through its texel view: entry e's ray
// in texels 2e and 2e + 1, its hit in texel 2 * entries + e, its path index in word e from texel 3 * entries, and the
// entry of its path's next bounce in word e from the texel after those (HT_NO_BOUNCE: none).
uvec4 cached_bounce_hit(uint e) { return texelFetch(reuseBounceTexels, int(2u * FRAME.moved.w + e)); }
uint cached_bounce_next(uint e) {
  uint entries = FRAME.moved.w;
  return texelFetch(reuseBounceTexels, int(3u * entries + (entries + 3u) / 4u + e / 4u))[e % 4u];
}
// Is `ray` the cached ray of entry e, bit for bit?
bool is_cached_bounce_ray(uint e, HtRay ray) {
  uvec4 a = texelFetch(reuseBounceTexels, int(2u * e)), b = texelFetch(reuseBounceTexels, int(2u * e + 1u));
  return a == floatBitsToUint(vec4(ray.origin, ray.tmin)) && b == floatBitsToUint(vec4(ray.dir, ray.tmax));
}
// The entry of frame path `framePath`'s ray at this dispatch's depth (>= 1), from its first link (FRAME.bounceFirst)
// along the next links; HT_NO_BOUNCE when the frame that filled the cache ended the path sooner or the path was
// re-traced since.
uint cached_bounce_entry(uint framePath) {
  uint e = UintRef(FRAME.bounceFirst).v[framePath];
  for (uint d = 1u; d < pc.depth && e != HT_NO_BOUNCE; ++d) e = cached_bounce_next(e);
  return e;
}

// The shadow-occlusion cache's word (gpu/wavefront_types.h HT_OCCLUSION_TRACED_SHIFT) of frame path `framePath` at
// this dispatch's depth; occlusion_word_index: of batch path `batchPath` (`listed`: the batch traces listed targets).
uint occlusion_word_of_frame_path(uint framePath) { return pc.depth * FRAME.dims.w * FRAME.dims.z + framePath; }
uint occlusion_word_index(uint batchPath, bool listed) {
  return occlusion_word_of_frame_path(listed ? listed_frame_path(batchPath) : pc.batchFirst + batchPath);
}
