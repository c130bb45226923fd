#include "core/composition.h"

#include <algorithm>

namespace vsil {

const char* compositionName(Composition composition) {
  switch (composition) {
    case Composition::PairReduce:
      return "pair-reduce";
    case Composition::MaxReduce:
      return "max-reduce";
    case Composition::LocalMaxReduce:
      return "local-max-reduce";
    case Composition::Relay:
      return "relay";
    case Composition::None:
      return "none";
  }
  return "none";
}

namespace composition {

PixelState decide(PixelState t, PixelState c) {
  switch (t) {
    case PixelState::Empty:
      return c;
    case PixelState::Filled:
      return PixelState::Filled;
    case PixelState::Contour:
      if (c == PixelState::Empty) return PixelState::Silhouette;
      if (c == PixelState::Filled) return PixelState::Filled;
      return PixelState::Contour;
    case PixelState::Silhouette:
      return PixelState::Silhouette;
  }
  return t;
}

float NkRun::depth() const {
  return t == PixelState::Silhouette ? 0.5f * (hit + detectPrev) : hit;
}

NkRun foldNk(std::span<const NkSample> samples) {
  NkRun run;
  for (const NkSample& s : samples) {
    if (!run.first) run.first = s.c;
    const PixelState next = decide(run.t, s.c);
    if (run.t == PixelState::Empty && next != PixelState::Empty) {
      run.hit = s.depth;
    } else if (run.t == PixelState::Contour && next == PixelState::Silhouette) {
      run.detectPrev = run.last;
    }
    run.t = next;
    run.last = s.depth;
  }
  return run;
}

NkRun combine(const NkRun& front, const NkRun& back) {
  if (!front.first) return back;
  if (!back.first) return front;
  NkRun out = front;
  out.last = back.last;
  switch (front.t) {
    case PixelState::Empty:
      out = back;
      out.first = front.first;
      return out;
    case PixelState::Filled:
    case PixelState::Silhouette:
      return out;
    case PixelState::Contour:
      if (*back.first == PixelState::Empty) {
        out.t = PixelState::Silhouette;
        out.detectPrev = front.last;
      } else if (*back.first == PixelState::Filled) {
        out.t = PixelState::Filled;
      } else {
        out.t = back.t;
        out.detectPrev = back.detectPrev;
      }
      return out;
  }
  return out;
}

MaxRun foldMax(std::span<const float> values, std::span<const float> depths) {
  MaxRun run;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!run.any || values[i] > run.value) run = {true, values[i], depths[i]};
  }
  return run;
}

MaxRun combine(const MaxRun& front, const MaxRun& back) {
  if (!back.any) return front;
  if (!front.any) return back;
  return back.value > front.value ? back : front;
}

LmipRun foldLmip(std::span<const float> values, std::span<const float> depths, float threshold) {
  LmipRun run;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float s = values[i];
    if (!run.any) {
      run.any = true;
      run.first = s;
      run.max = s;
    }
    run.max = std::max(run.max, s);
    if (run.done) continue;
    if (run.hasTop && s < run.top) {
      run.done = true;
      continue;
    }
    if (s >= threshold && (!run.hasTop || s > run.top)) {
      run.hasTop = true;
      run.top = s;
      run.topDepth = depths[i];
    }
  }
  return run;
}

LmipRun combine(const LmipRun& front, const LmipRun& back) {
  if (!back.any) return front;
  if (!front.any) return back;
  LmipRun out = front;
  out.max = std::max(front.max, back.max);
  if (front.done) return out;
  if (!front.hasTop) {
    LmipRun b = back;
    b.first = front.first;
    b.max = out.max;
    return b;
  }
  if (back.first < front.top) {
    out.done = true;
    return out;
  }
  // back.first >= T >= threshold: the back started its own run there, and goes on as the
  // front's would; where it never rose above T the front's sample stays the highest.
  LmipRun b = back;
  b.first = front.first;
  b.max = out.max;
  if (!(back.top > front.top)) {
    b.top = front.top;
    b.topDepth = front.topDepth;
  }
  return b;
}

}  // namespace composition
}  // namespace vsil
