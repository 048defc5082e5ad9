#version 460
#extension GL_GOOGLE_include_directive : require
// shade: Whitted shading of the closest hits of the current queue (one invocation per queue entry).
//   miss     -> background radiance
//   any hit  -> emission
//   diffuse  -> ambient term + one shadow ray per punctual light (traced by trace_any, summed by gather_direct)
//   mirror   -> continue along the reflection (throughput *= base colour)
//   glass    -> continue along the reflection or the refraction, chosen with the exact dielectric Fresnel
//               probability (so each path stays one ray and the estimator is unbiased over samples)
// Specialisation constants compile out what the scene lacks; the host also skips the passes they would feed.
#include "gpu/shaders/common.glsl"
#extension GL_KHR_shader_subgroup_ballot : require
#include "bvh/offset_ray.h"
#include "gpu/convex_parts.h"
#include "gpu/segment_cells.h"
#include "gpu/shaders/reuse_cache.glsl"

layout(constant_id = 0) const bool HAS_LIGHTS = true;
layout(constant_id = 1) const bool HAS_MIRROR = true;
layout(constant_id = 2) const bool HAS_GLASS = true;
layout(constant_id = 3) const bool HAS_TEXTURES = true;
// The shadow-occlusion cache (docs/REUSE.md §3-4; modes HT_OCCLUSION_* in gpu/wavefront_types.h): with OCCLUSION !=
// OFF, shade writes the word of each path it shades: a ray it takes from the cache keeps its bits, every other bit
// is cleared, and trace_any sets those of the rays it traces (SHADOW_CACHE). A ray whose recorded occlusion holds gets what trace_any would give its
// slot and is not queued (its slot's w = 2: live, not traced), so trace_any's subgroups hold only rays it traces.
//   RECORD: nothing is taken from the cache.
//   KEPT_LIGHTS (a frame re-shaded from cached hits after a light edit): the path's hit is the recorded one, so a ray
//     to a light in FRAME.frame.w (its position and direction unchanged) is the recorded ray, in unchanged geometry.
//   KEPT_SEGMENTS (depth 0 of a partial re-render after a node move): a ray whose path kept its cached primary hit
//     (the same surface point and lights, so the same ray) and whose segment avoids the padded moved bounds (no moved
//     triangle can meet it). One whose segment meets them and that was unoccluded is queued with HT_SHADOW_MOVED_ONLY
//     where the moved instances are known: no unmoved triangle meets it, so trace_any walks the moved ones alone.
layout(constant_id = 4) const uint OCCLUSION = HT_OCCLUSION_OFF;
// Depth 0 of a frame re-shaded from cached hits: the primary rays and hits are read from the cache in place (path
// order, from pc.batchFirst) rather than copied into queue 0 and the hit buffer first (the copies cost lavapipe
// about 10 ms on the HPO wall); no other pass of such a frame reads them at depth 0.
layout(constant_id = 5) const bool HITS_FROM_CACHE = false;
// A frame that fills the bounce cache (ReusePlan::recordSecondary) links each path's entries: the entry of its next
// bounce is the first entry the next depth's queue will take (FRAME.bounceLinks.y) plus the slot shade appends it to,
// HT_NO_BOUNCE when the path ends here; at depth 0 that link is the path's first (FRAME.bounceFirst, by frame path),
// at depth d >= 1 the next link of the entry of queue slot i, FRAME.bounceLinks.x + i (FRAME.bounceNext).
layout(constant_id = 6) const bool LINK_BOUNCES = false;

const float HT_INV_PI = 0.31830988618379067154f;
const float HT_RAY_FAR = 3.0e38f;

// Appends `want` lanes to a queue with one atomic per subgroup; returns the lane's slot (undefined if !want).
uint append_slot(bool want, uint counterSelect) {
  uvec4 ballot = subgroupBallot(want);
  uint total = subgroupBallotBitCount(ballot);
  uint base = 0u;
  if (subgroupElect() && total > 0u) {
    base = counterSelect == 2u ? atomicAdd(COUNTERS.shadowCount, total)
                               : atomicAdd(COUNTERS.queueCount[counterSelect], total);
  }
  base = subgroupBroadcastFirst(base);
  return base + subgroupBallotExclusiveBitCount(ballot);
}

// Bilinear lookup with repeat wrapping; texels are linear RGBA, row 0 = glTF v = 0.
vec3 sample_texture(uint index, vec2 uv) {
  GpuTexture tex = scene_texture(index);
  vec2 size = vec2(float(tex.info.y), float(tex.info.z));
  vec2 p = fract(uv) * size - 0.5f;
  vec2 f = fract(p);
  ivec2 p0 = ivec2(floor(p));
  vec3 c = vec3(0.0f);
  for (int k = 0; k < 4; ++k) {
    ivec2 q = p0 + ivec2(k & 1, k >> 1);
    uint x = uint((q.x % int(tex.info.y) + int(tex.info.y)) % int(tex.info.y));
    uint y = uint((q.y % int(tex.info.z) + int(tex.info.z)) % int(tex.info.z));
    float w = ((k & 1) == 1 ? f.x : 1.0f - f.x) * ((k >> 1) == 1 ? f.y : 1.0f - f.y);
    c += w * scene_texel(tex.info.x + y * tex.info.y + x).xyz;
  }
  return c;
}

struct SurfacePoint {
  vec3 p;        // position from barycentrics (more accurate than o + t*d far from the origin)
  vec3 nFace;    // geometric normal facing the incoming ray
  vec3 nShade;   // interpolated shading normal on the same side as nFace
  bool front;    // the ray hit the side the triangle's winding faces
  vec2 uv;
  uint material;
  float convexTag;  // its convex part and the sides outside it (gpu/convex_parts.h; 0: none)
};

SurfacePoint surface_point(HtHit hit, vec3 dir) {
  uvec4 tri = scene_triangle(hit.triId);
  vec4 tagged0 = scene_vertex_tagged(tri.x);
  vec3 p0 = tagged0.xyz, p1 = scene_vertex(tri.y), p2 = scene_vertex(tri.z);
  float w0 = 1.0f - hit.u - hit.v;
  SurfacePoint s;
  s.p = w0 * p0 + hit.u * p1 + hit.v * p2;
  vec3 ng = normalize(cross(p1 - p0, p2 - p0));
  s.front = dot(dir, ng) < 0.0f;
  s.nFace = s.front ? ng : -ng;
  s.nShade = s.nFace;
  if (FRAME.flags.x != 0u) {
    vec3 n = w0 * scene_normal(tri.x) + hit.u * scene_normal(tri.y) + hit.v * scene_normal(tri.z);
    float len = length(n);
    if (len > 0.0f) {
      n /= len;
      s.nShade = dot(n, s.nFace) < 0.0f ? -n : n;
    }
  }
  s.uv = vec2(0.0f);
  if (HAS_TEXTURES && FRAME.flags.y != 0u) {
    s.uv = w0 * scene_texcoord(tri.x) + hit.u * scene_texcoord(tri.y) + hit.v * scene_texcoord(tri.z);
  }
  s.material = tri.w;
  s.convexTag = tagged0.w;
  return s;
}

// The convex part (gpu/convex_parts.h) a ray from `s` leaves on its outside, 0 for none: one whose origin is offset to
// nFace's side (`sameSide`, a reflection or a shadow ray) or to the other side (a refraction) and whose direction
// moves away from the triangle's plane on that side. (The shading normal can turn a glass ray across the plane: such a
// ray crosses the surface and may meet its part.)
uint leaves_surface(SurfacePoint s, vec3 dir, bool sameSide) {
  float away = dot(dir, s.nFace);
  bool leaving = sameSide ? away > 0.0f : away < 0.0f;
  return leaving ? ht_convex_part_left(s.convexTag, sameSide == s.front) : 0u;
}

// Incident radiance scale and direction of light l at p (KHR_lights_punctual recommended falloffs).
vec3 light_incidence(GpuLight light, vec3 p, out vec3 wi, out float dist) {
  uint type = uint(light.position.w);
  if (type == HT_LIGHT_DIRECTIONAL) {
    wi = -light.direction.xyz;
    dist = HT_RAY_FAR;
    return light.radiance.xyz;
  }
  vec3 d = light.position.xyz - p;
  float d2 = dot(d, d);
  dist = sqrt(d2);
  wi = d / dist;
  vec3 e = light.radiance.xyz / max(d2, 1e-20f);
  float range = light.direction.w;
  if (range > 0.0f) {
    float r = dist / range;
    e *= clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  }
  if (type == HT_LIGHT_SPOT) {
    float cd = dot(light.direction.xyz, -wi);
    float t = clamp((cd - light.cone.x) / max(light.cone.y - light.cone.x, 1e-6f), 0.0f, 1.0f);
    e *= t * t;
  }
  return e;
}

// Emits the path's shadow rays; returns the word of the occlusion cache to store (OCCLUSION != OFF).
// `occlusionIndex`: the path's word in the occlusion cache (occlusion_word_index).
uint emit_shadow_rays(uint path, SurfacePoint s, vec3 weight, uint occlusionIndex) {
  uint lightCount = FRAME.scene.x;
  vec3 origin = ht_offset_ray(s.p, s.nFace);
  uint word = 0u;      // the path's recorded word
  uint holding = 0u;   // bit l: light l's recorded occlusion holds (if the ray's segment allows, KEPT_SEGMENTS)
  if (OCCLUSION == HT_OCCLUSION_KEPT_LIGHTS || OCCLUSION == HT_OCCLUSION_KEPT_SEGMENTS) {
    // KEPT_SEGMENTS (depth 0 of a partial re-render): trace_closest.comp cleared the word of every path whose
    // primary ray it traced again, so a word that holds bits belongs to a path that kept its cached hit.
    word = UintRef(FRAME.shadowOcclusion).v[occlusionIndex];
    holding = word >> HT_OCCLUSION_TRACED_SHIFT;
    if (OCCLUSION == HT_OCCLUSION_KEPT_LIGHTS) holding &= FRAME.frame.w;
    if (OCCLUSION == HT_OCCLUSION_KEPT_SEGMENTS) load_moved_view();
  }
  uint taken = 0u;  // bit l: light l's slot takes the recorded occlusion
  for (uint l = 0u; l < lightCount; ++l) {
    vec3 wi;
    float dist;
    vec3 e = light_incidence(scene_light(l), s.p, wi, dist);
    float cosTheta = dot(s.nShade, wi);
    vec3 contrib = weight * e * max(cosTheta, 0.0f);
    bool want = cosTheta > 0.0f && dot(s.nFace, wi) > 0.0f && max(contrib.x, max(contrib.y, contrib.z)) > 0.0f;
    bool recorded = want && (holding & (1u << l)) != 0u;
    uint movedOnly = 0u;  // HT_SHADOW_MOVED_ONLY: trace_any walks the moved instances alone
    if (OCCLUSION == HT_OCCLUSION_KEPT_SEGMENTS && recorded) {
      bool meets = ht_segment_meets_box(origin, wi, 0.0f, dist, moved_lo(), moved_hi());
      // The same ray, unoccluded before the move: no unmoved triangle meets it, so only a moved one can now.
      if (meets && (word & (1u << l)) == 0u && moved_instances_known()) movedOnly = HT_SHADOW_MOVED_ONLY;
      recorded = !meets;
    }
    uint q = append_slot(want && !recorded, 2u);
    if (want) {
      uint slot = path * lightCount + l;
      // record_segments reads the queued rays, and in a partial re-render every live one
      if (!recorded || OCCLUSION == HT_OCCLUSION_KEPT_SEGMENTS) store_shadow_ray(slot, HtRay(origin, 0.0f, wi, dist));
      if (recorded) {
        taken |= 1u << l;
        bool occluded = (word & (1u << l)) != 0u;
        imageStore(shadowContribBuffer, int(slot), occluded ? vec4(0.0f, 0.0f, 0.0f, 2.0f) : vec4(contrib, 2.0f));
      } else {
        imageStore(shadowContribBuffer, int(slot), vec4(contrib, 1.0f));
        imageStore(shadowQueueBuffer, int(q), uvec4(slot | movedOnly, leaves_surface(s, wi, true), 0u, 0u));
      }
    }
  }
  return word & (taken | (taken << HT_OCCLUSION_TRACED_SHIFT));
}

// Exact unpolarised Fresnel reflectance of a dielectric interface (pbrt-v4 FrDielectric).
float fresnel_dielectric(float cosI, float cosT, float eta) {
  float rParl = (cosI - eta * cosT) / (cosI + eta * cosT);
  float rPerp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5f * (rParl * rParl + rPerp * rPerp);
}

// The key of chunk path `chunkPath` (target x sample; in the refinement pass or a partial re-render, listed target x
// sample) for its random choices (glass: reflect or refract). Keyed by the target's index in the whole frame and the
// path's absolute sample index (samples accumulated so far + its sample in this pass), without the pass's spp, as
// footprint_sample_progressive keys its position: a single frame of N samples, a partial re-render of it, and k
// progressive frames of N/k samples all draw the same choices (docs/REUSE.md §6 item 3), so the progressive frame at
// N samples is the single frame's bits; a refined target's samples stay those of a frame at the refinement spp.
// Independent of how the frame is cut into chunks of views or bands of rows (common.glsl frame_global_target).
uint path_sample_key(uint chunkPath) {
  uint spp = FRAME.dims.z;
  uint entry = chunkPath / spp;
  bool listed = FRAME.refineInfo.y != 0u;  // listed targets: refinement, a progressive list or a partial re-render
  uint target = listed ? UintRef(FRAME.refine).v[FRAME.refineInfo.y + entry] : entry;
  uint globalTarget = frame_global_target(target);
  uint sampleIndex = (FRAME.accum.x != 0u ? accum_samples_so_far(globalTarget) : 0u) + chunkPath % spp;
  return ht_hash(globalTarget * 0x9E3779B9u ^ ht_hash(sampleIndex ^ 0x5BD1E995u));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= COUNTERS.queueCount[pc.queue]) return;
  uint path = queue_path(i);
  HtRay ray;
  HtHit hit;
  if (HITS_FROM_CACHE) {
    ray = cached_primary_ray(pc.batchFirst + i);
    hit = cached_primary_ht_hit(pc.batchFirst + i);
  } else {
    ray = load_ray(pc.queue, i);
    hit = load_hit(i);
  }
  vec3 throughput = path_throughput(path);
  vec3 radiance = vec3(0.0f);
  bool hitSurface = hit.triId != HT_MISS;
  bool wantShadows = false;
  bool continues = false;
  vec3 dir = normalize(ray.dir);
  HtRay next;
  uint nextLeaves = 0u;  // the convex part `next` leaves on its outside (trace_closest skips it)
  SurfacePoint s;
  vec3 albedo = vec3(0.0f);
  if (!hitSurface) {
    radiance = throughput * FRAME.background.xyz;
  } else {
    s = surface_point(hit, dir);
    GpuMaterial m = scene_material(s.material);
    albedo = m.baseColor.xyz;
    if (HAS_TEXTURES && m.baseColor.w >= 0.0f) albedo *= sample_texture(uint(m.baseColor.w), s.uv);
    radiance = throughput * m.emissive.xyz;
    uint kind = uint(m.emissive.w);
    bool last = pc.depth >= FRAME.scene.w;
    if (HAS_MIRROR && kind == HT_MATERIAL_MIRROR) {
      continues = !last;
      vec3 r = reflect(dir, s.nShade);
      if (dot(r, s.nFace) <= 0.0f) r = reflect(dir, s.nFace);
      next = HtRay(ht_offset_ray(s.p, s.nFace), 0.0f, r, HT_RAY_FAR);
      nextLeaves = leaves_surface(s, next.dir, true);
      throughput *= albedo;
    } else if (HAS_GLASS && kind == HT_MATERIAL_GLASS) {
      continues = !last;
      float eta = s.front ? 1.0f / m.params.w : m.params.w;  // n_incident / n_transmitted
      float cosI = -dot(dir, s.nShade);
      float sin2T = eta * eta * max(0.0f, 1.0f - cosI * cosI);
      bool reflectRay = sin2T >= 1.0f;  // total internal reflection
      float cosT = sqrt(max(0.0f, 1.0f - sin2T));
      if (!reflectRay) {
        uint h = ht_hash(path_sample_key(pc.batchFirst + path) ^ ht_hash(pc.depth * 0x632BE5ABu ^ FRAME.frame.x));
        reflectRay = ht_uint_to_unit(h) < fresnel_dielectric(cosI, cosT, eta);
      }
      if (reflectRay) {
        next = HtRay(ht_offset_ray(s.p, s.nFace), 0.0f, reflect(dir, s.nShade), HT_RAY_FAR);
      } else {
        vec3 t = eta * dir + (eta * cosI - cosT) * s.nShade;
        next = HtRay(ht_offset_ray(s.p, -s.nFace), 0.0f, normalize(t), HT_RAY_FAR);
      }
      nextLeaves = leaves_surface(s, next.dir, reflectRay);
      throughput *= albedo;
    } else {
      radiance += throughput * albedo * FRAME.ambient.xyz;
      wantShadows = HAS_LIGHTS;
    }
    continues = continues && max(throughput.x, max(throughput.y, throughput.z)) > 1e-4f;
  }
  add_path_radiance(path, radiance);

  // Subgroup operations act on the lanes active at the call, so each divergent group appends for itself.
  uint occlusionWord = 0u;  // a path without shadow rays here has no recorded occlusion here
  uint occlusionIndex =
      OCCLUSION != HT_OCCLUSION_OFF ? occlusion_word_index(path, OCCLUSION == HT_OCCLUSION_KEPT_SEGMENTS) : 0u;
  if (HAS_LIGHTS && wantShadows) {
    occlusionWord = emit_shadow_rays(path, s, throughput * albedo * HT_INV_PI, occlusionIndex);
  }
  if (OCCLUSION != HT_OCCLUSION_OFF) UintRef(FRAME.shadowOcclusion).v[occlusionIndex] = occlusionWord;
  if (HAS_MIRROR || HAS_GLASS) {
    uint out_queue = 1u - pc.queue;
    uint q = append_slot(continues, out_queue);
    if (continues) {
      store_ray(out_queue, q, next);
      store_queue_path(out_queue, q, path);
      store_queue_leaves(out_queue, q, nextLeaves);
      imageStore(throughputBuffer, int(path), vec4(throughput, 0.0f));
    }
    if (LINK_BOUNCES) {  // (addresses 0 once the cache overflowed: the frame then keeps no state)
      uint link = continues ? FRAME.bounceLinks.y + q : HT_NO_BOUNCE;
      if (PRIMARY_DEPTH) {
        if (FRAME.bounceFirst != 0ul) UintRef(FRAME.bounceFirst).v[pc.batchFirst + path] = link;
      } else if (FRAME.bounceNext != 0ul) {
        UintRef(FRAME.bounceNext).v[FRAME.bounceLinks.x + i] = link;
      }
    }
  }
}
