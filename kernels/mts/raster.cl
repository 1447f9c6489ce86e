// The raster kernel: a row's pieces, their end codes, the pixel loop.

// The fight mask of a piece [x, x_end) whose fragments are all covered and inside (finite,
// unclipped): codes compared, or depths where the band is MTS_D_ORDERED, or plane A's cached codes
// (ca, CACHE_A_CODES) against B's. A piece of 16 pixels or more is taken in chunks of 16 from x,
// the last one ending at x_end: it overlaps the one before, and evaluating pixels of the same
// piece twice leaves the OR as it is, so no lane needs masking. A shorter piece is one chunk with
// the lanes past its end off.
// always_inline: with two call sites PoCL's compiler kept it out of line (its own symbol in perf),
// and log_fragment's at_mts went from 1.8 to 2.2 ns/pair; inlined, 1.4.
__attribute__((always_inline)) static inline int16 inside_piece16(row_plane16_t ra,
                                                                  row_plane16_t rb,
                                                                  __global const float* P, float ox,
                                                                  int x, int x_end, int ordered,
                                                                  __global const uint* ca) {
  /* pixel centres step by exactly 16: ox is an integer and coordinates stay below 2^15
   * (host/model/scene.cpp kMaxKernelSide), so (ox + idx) + 0.5f is exact for every idx */
#define PX16(I0) ((ox + convert_float16((I0) + LANES)) + 0.5f)
#define PIECE_FIGHTS(FIGHT16)                                                                  \
  {                                                                                            \
    if (x_end - x < 16) return ((x + LANES) < x_end) & FIGHT16(PX16(x), x);                    \
    int16 fight_ = (int16)0;                                                                   \
    const float16 px0_ = PX16(x);                                                              \
    float16 px_ = px0_;                                                                        \
    for (int i0_ = x; i0_ < x_end - 16; i0_ += 16, px_ += 16.0f) fight_ |= FIGHT16(px_, i0_);  \
    return fight_ | FIGHT16(px0_ + (float)(x_end - 16 - x), x_end - 16); /* exact, as above */ \
  }
#define CACHED_FIGHTS16(PX, I0) fights16(vload16(0, ca + (I0)), inside_code16(rb, P, (PX)))
#define ORDERED_FIGHTS16(PX, I0) ordered_fights16(depth16(ra, P, (PX)).d, depth16(rb, P, (PX)).d)
#define CODE_FIGHTS16(PX, I0) fights16(inside_code16(ra, P, (PX)), inside_code16(rb, P, (PX)))
#if CACHE_A_CODES
  if (ca) PIECE_FIGHTS(CACHED_FIGHTS16)
#endif
  if (ordered)
    PIECE_FIGHTS(ORDERED_FIGHTS16) /* a loop of its own: a select inside one would
                                       compute both sides */
  PIECE_FIGHTS(CODE_FIGHTS16)
#undef CODE_FIGHTS16
#undef ORDERED_FIGHTS16
#undef CACHED_FIGHTS16
#undef PIECE_FIGHTS
#undef PX16
}

// The kernel rows of one (probe, frame). A row splits into pieces where both planes' covering
// triangles stay the same; within a piece each plane's depth is one plane equation, monotone in
// px (every rounding step of it is monotone), and so is its stored code. The ends of all pieces
// are evaluated together, 16 pieces per vector: a piece whose end codes already exclude a fight
// (LEQUAL: B's smaller end code above A's larger) is decided without touching its inside, and a
// piece of one or two pixels is decided by its ends outright. Only the rest is evaluated pixel by
// pixel, 16 at a time. Log depth is monotone only up to the library log's error (OpenCL 1.2
// allows 3 ulp): its end codes must clear the bound by LOG_CODE_SLACK
// (host/runtime/kernel_variant.cpp), the most codes that error can move a code either way at both
// ends of both planes. Pieces are then taken left to right and the row stops after the first that
// fights. In a band mts_frame_bounds certified inside (MTS_D_INSIDE, MTS_D_ORDERED) there is no end
// pass, and the whole row is evaluated first with one reduction; only a row that fights is then
// taken piece by piece. A work-item takes a band's rows one after the other, so a band decided
// clean from code bounds (most of a search's descent) costs one work-item, not one per row. Global
// id: (band, visit, probe); results at (probe * frames + visit) * kernel_h + row.
__kernel void mts_raster(MTS_RASTER_BUFFERS(MTS_ARG_IN, MTS_ARG_OUT) const MtsRasterArgs args) {
  const uint first_frame = args.first_frame, frames_total = args.frames_total;
  const uint frames = args.frames, shortcuts = args.shortcuts;
  const uint kernel_w = args.area.kernel_w, kernel_h = args.area.kernel_h;
  const uint bands = args.area.bands, band_rows = args.area.band_rows;
  const float origin_x = args.area.origin_x, origin_y = args.area.origin_y;
  const uint band = get_global_id(0), visit = get_global_id(1), probe = get_global_id(2);
  if (band >= bands) return;
  const uint r0 = band * band_rows, r1 = min(kernel_h, r0 + band_rows);
  const uint pf = probe * frames + visit;
  const uint ap = a_plane(a_slots, probe, visit, first_frame, frames_total);
  const int nonfinite = (a_vflags[ap] | vflags[pf]) & MTS_V_NONFINITE;
  __global const float* P = probes + probe * MTS_PROBE_STRIDE;
  __global const uint* dec = decided + (size_t)(pf * bands + band) * MTS_DECIDED_WORDS;
  __global const float* TA = a_tris + (size_t)ap * PLANE_STRIDE;
  __global const float* TBp = tris + (size_t)pf * PLANE_STRIDE;
  const int W = (int)kernel_w;
  for (uint row = r0; row < r1; ++row) {
    const uint id = pf * kernel_h + row;
    if (nonfinite) {
      result[id] = MTS_R_NONFINITE;
      continue;
    }
    /* a row with a vertex near a pixel centre is outside its band's verdict */
    const uint band_verdict =
        (dec[MTS_DW_BAD_ROWS] >> (row - r0)) & 1u ? MTS_D_RASTER : dec[MTS_DW_VERDICT] & MTS_D_MASK;
    if (band_verdict == MTS_D_CLEAN) { /* clean from code bounds: mts_frame_bounds */
      result[id] = MTS_R_BOUNDS | (kernel_w << MTS_R_COUNT_SHIFT);
      continue;
    }
    const float py = origin_y + (float)row + 0.5f;
    __global const uint* rec = a_rows + ((size_t)ap * kernel_h + row) * MTS_ROW_WORDS;
    const int cached = rec[MTS_RW_N] > 0u;
    const int b_is_a = shortcuts && cached &&
                       b_coverage_is_a(((__global const float*)dec)[MTS_DW_MOVED],
                                       dec[MTS_DW_VERDICT] & MTS_DV_ORIENTED, TBp, vflags[pf],
                                       (int)row, band_rows, rec);
    const int inside = band_verdict == MTS_D_INSIDE || band_verdict == MTS_D_ORDERED;
    const int ordered = band_verdict == MTS_D_ORDERED;
#if CACHE_A_CODES
    __global const uint* ca =
        cached && args.a_codes_filled
            ? a_codes + ((size_t)ap * kernel_h + row) * (kernel_w + MTS_CODE_ROW_PAD)
            : 0;
#else
    __global const uint* ca = 0;
#endif
    if (inside && b_is_a) {
      /* The common row near the MTS: every piece covered and inside, and the pieces are plane A's
       * cached segments, taken straight from the record, one reduction for the whole row. A row
       * that fights goes on below, which finds its first fighting piece (and so its count). */
      const int n = (int)rec[MTS_RW_N];
      int16 fight = (int16)0;
      for (int k = 0; k < n; ++k) {
        const int t = (int)rec[MTS_RW_T + k];
        fight |= inside_piece16(broadcast16(row_plane(TA, t, py)),
                                broadcast16(row_plane(TBp, t, py)), P, origin_x,
                                (int)rec[MTS_RW_X + k], (int)rec[MTS_RW_X + k + 1], ordered, ca);
      }
      if (!any16(fight)) {
        result[id] = MTS_R_REUSED | ((rec[MTS_RW_X + n] - rec[MTS_RW_X]) << MTS_R_COUNT_SHIFT);
        continue;
      }
    }
    int seg_xa[MAX_SEG + 1], seg_ta[MAX_SEG], seg_xb[MAX_SEG + 1], seg_tb[MAX_SEG];
    const int na = cached ? record_segments(rec, seg_xa, seg_ta)
                          : row_segments(TA, py, origin_x, W, seg_xa, seg_ta);

    /* the pieces, and the end-point verdict of each: R_* bits, or ~0u for "look inside" */
    int px_start[MAX_PIECES], px_end[MAX_PIECES], p_ta[MAX_PIECES], p_tb[MAX_PIECES];
    uint verdict[MAX_PIECES];
    int ends_ok[MAX_PIECES]; /* both planes finite and unclipped at both ends, so inside too */
    int np = 0;
    if (b_is_a) { /* B's segments are A's: the pieces are A's segments, no merge needed */
      for (int k = 0; k < na; ++k)
        if (seg_xa[k + 1] > seg_xa[k]) {
          px_start[np] = seg_xa[k];
          px_end[np] = seg_xa[k + 1];
          p_ta[np] = p_tb[np] = seg_ta[k];
          ++np;
        }
    } else {
      row_segments(TBp, py, origin_x, W, seg_xb, seg_tb);
      FOR_EACH_PIECE({
        px_start[np] = x;
        px_end[np] = x_end;
        p_ta[np] = ta;
        p_tb[np] = tb;
        ++np;
      })
    }
    if (inside) {
      if (!b_is_a) { /* as above, over the merged pieces (b_is_a rows here are known to fight) */
        int16 fight = (int16)0;
        uint all = 0u;
        for (int i = 0; i < np; ++i) {
          fight |= inside_piece16(broadcast16(row_plane(TA, p_ta[i], py)),
                                  broadcast16(row_plane(TBp, p_tb[i], py)), P, origin_x,
                                  px_start[i], px_end[i], ordered, ca);
          all += (uint)(px_end[i] - px_start[i]);
        }
        if (!any16(fight)) {
          result[id] = all << MTS_R_COUNT_SHIFT;
          continue;
        }
      }
      for (int i = 0; i < np; ++i) { /* a row that fights: its pieces one by one, below */
        verdict[i] = ~0u;
        ends_ok[i] = 1;
      }
    } else
      for (int g = 0; g < np; g += 16) {
        row_plane_lanes_t la, lb;
        float e0[16], e1[16];
        for (int k = 0; k < 16; ++k) {
          const int i = min(g + k, np - 1);
          set_lane(&la, k, row_plane(TA, max(p_ta[i], 0), py));
          set_lane(&lb, k, row_plane(TBp, max(p_tb[i], 0), py));
          e0[k] = origin_x + (float)px_start[i] + 0.5f;
          e1[k] = origin_x + (float)(px_end[i] - 1) + 0.5f;
        }
        const row_plane16_t ra = load_lanes(&la), rb = load_lanes(&lb);
        const float16 p0 = vload16(0, e0), p1 = vload16(0, e1);
        const frag16_t a0 = fragment16(ra, P, p0), a1 = fragment16(ra, P, p1);
        const frag16_t b0 = fragment16(rb, P, p0), b1 = fragment16(rb, P, p1);
        const int16 nf = a0.nonfinite | a1.nonfinite | b0.nonfinite | b1.nonfinite;
        const int16 cl = a0.clipped | a1.clipped | b0.clipped | b1.clipped;
        const int16 fight_ends = fights16(a0.code, b0.code) | fights16(a1.code, b1.code);
        const ulong16 slack = (ulong16)LOG_SLACK_OR_0;
#if !PLANE_MONOTONE
        const int16 excluded = (int16)0;
#elif COMPARE_GREATER
        const int16 excluded = convert_int16(convert_ulong16(max(b0.code, b1.code)) + slack <
                                             convert_ulong16(min(a0.code, a1.code)));
#else
        const int16 excluded = convert_int16(convert_ulong16(min(b0.code, b1.code)) >
                                             convert_ulong16(max(a0.code, a1.code)) + slack);
#endif
        int nfk[16], clk[16], fek[16], exk[16];
        vstore16(nf, 0, nfk);
        vstore16(cl, 0, clk);
        vstore16(fight_ends, 0, fek);
        vstore16(excluded, 0, exk);
        for (int k = 0; k < 16 && g + k < np; ++k) {
          const int i = g + k;
          const int len = px_end[i] - px_start[i];
          uint v = ~0u;
          if (len <= 2) { /* the ends are the whole piece */
            v = nfk[k] ? MTS_R_NONFINITE : clk[k] ? MTS_R_CLIPPED : fek[k] ? MTS_R_FIGHT : 0u;
          } else if (!nfk[k] && !clk[k] && exk[k]) {
            v = 0u;
          }
          verdict[i] = v;
          ends_ok[i] = PLANE_MONOTONE && !nfk[k] && !clk[k];
        }
      }

    uint flags = 0u, count = 0u;
    for (int i = 0; i < np; ++i) {
      const int x = px_start[i], x_end = px_end[i];
      count += (uint)(x_end - x);
      if (p_ta[i] < 0 || p_tb[i] < 0) {
        flags |= MTS_R_UNCOVERED;
        continue;
      }
      uint piece = verdict[i];
      if (piece == ~0u) {
        piece = 0u;
        const row_plane16_t ra = broadcast16(row_plane(TA, p_ta[i], py));
        const row_plane16_t rb = broadcast16(row_plane(TBp, p_tb[i], py));
        if (ends_ok[i]) { /* only the codes matter: one reduction per piece */
          piece =
              any16(inside_piece16(ra, rb, P, origin_x, x, x_end, ordered, ca)) ? MTS_R_FIGHT : 0u;
        } else
          for (int i0 = x; i0 < x_end; i0 += 16) {
            const int16 idx = i0 + LANES;
            const int16 active = idx < x_end;
            const float16 px = (origin_x + convert_float16(idx)) + 0.5f;
            const frag16_t fa = fragment16(ra, P, px), fb = fragment16(rb, P, px);
            const int16 nf = active & (fa.nonfinite | fb.nonfinite);
            const int16 cl = active & ~nf & (fa.clipped | fb.clipped);
            const int16 ok = active & ~(fa.nonfinite | fb.nonfinite | fa.clipped | fb.clipped);
            piece |= (any16(nf) ? MTS_R_NONFINITE : 0u) | (any16(cl) ? MTS_R_CLIPPED : 0u) |
                     (any16(ok & fights16(fa.code, fb.code)) ? MTS_R_FIGHT : 0u);
          }
      }
      flags |= piece;
      if (piece & MTS_R_FIGHT) break;
    }
    result[id] = flags | (b_is_a ? MTS_R_REUSED : 0u) | (count << MTS_R_COUNT_SHIFT);
  }
}
