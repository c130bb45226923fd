// decision_inplace.frag (fast pipeline, pass 2 of 2): contour and decision table fused, the
// record updated in place, run only where this slice's footprint is FILLED.
// In:  the footprint (footprintTag() FILLED, anything else EMPTY); the depth buffer, where the
//      footprint pass wrote this slice's depth at FILLED pixels, limits the pass to those (early
//      test EQUAL).
// In/out: the record t (silhouette.glsl), read through recordTexture and written through
//      recordImage (the same texture). Each pixel reads and writes only its own record, so no
//      ping-pong is needed. (Reads go through the sampler because llvmpipe's imageLoad costs
//      far more than a texelFetch; a texture-fetch barrier between slices makes the stores
//      visible.) No colour output.
// Pixels that are not FILLED on a slice are not visited, so c = EMPTY is never applied here.
// The table's only effect of c = EMPTY is detection (CONTOUR -> SILHOUETTE); it is applied
// lazily instead: a CONTOUR record whose latest contour sample is not the previous slice met
// an empty slice since, and is a silhouette. finishState does the same for what remains.
layout(early_fragment_tests) in;
layout(binding = UNIT_RECORD) uniform sampler2D recordTexture;
layout(binding = IMAGE_RECORD, rgba32f) uniform writeonly restrict image2D recordImage;
layout(binding = UNIT_FOOTPRINT) uniform usampler2D footprintTexture;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 t = texelFetch(recordTexture, pixel, 0);
  uint state = uint(t.r);
  if (isFinal(state)) return;
  if (state == STATE_CONTOUR && t.a != previousSliceDepth) {
#ifdef SLAB_RUN
    // A slab's run keeps the hit and the contour's depth apart (composition::NkRun hit and
    // detectPrev): a run in front may still replace the hit.
    imageStore(recordImage, pixel, vec4(float(STATE_SILHOUETTE), t.g, t.b, t.a));
#else
    imageStore(recordImage, pixel, vec4(float(STATE_SILHOUETTE), silhouetteDepth(t), t.b, t.a));
#endif
    return;
  }
  imageStore(recordImage, pixel, decideRecord(t, contourAt(footprintTexture, pixel)));
}
