#!/usr/bin/env bash
# Renders the README's gallery, docs/images/*.png, from the classic datasets and gen: volumes: one
# small picture per look, each beside the paper figure it can be compared with (README, "Gallery").
#   scripts/gallery.sh [VSIL] [PREFIX]   (default build/vsil; datasets from $VSIL_SHARED_DIR or
#                                         ../shared; PREFIX: only the entries whose name starts so)
# Each entry is NAME|INPUT|OPTIONS. Add a technique's entries here when it lands; the README
# table names the same files. Deterministic: the same binary renders the same bytes.
set -euo pipefail
cd "$(dirname "$0")/.."
vsil=$(readlink -f "${1:-build/vsil}")
prefix=${2:-}
data=${VSIL_SHARED_DIR:-../shared}/datasets
[[ -x $vsil ]] || { echo "gallery: no vsil binary at $vsil (build first)" >&2; exit 2; }
[[ -d $data ]] || { echo "gallery: no datasets folder at $data" >&2; exit 2; }
out=docs/images
mkdir -p "$out"

common="--size 256x256"
entries=(
  # Nagy & Klein, Fig. 5-7: the right-angle method, the one-pixel silhouettes, broadened lines.
  "nk_engine_ra|$data/engine.vti|--technique rightangle --iso 80 --view 40,25 --width 2"
  "nk_engine_1px|$data/engine.vti|--iso 80 --view 40,25 --width 1"
  "nk_engine_w3|$data/engine.vti|--iso 80 --view 40,25 --width 3"
  "nk_neghip_ra|$data/neghip_64x64x64_uint8.nhdr|--technique rightangle --iso 64 --view 30,20 --zoom 1.3 --width 2"
  "nk_neghip_1px|$data/neghip_64x64x64_uint8.nhdr|--iso 64 --view 30,20 --zoom 1.3 --width 1"
  "nk_neghip_w3|$data/neghip_64x64x64_uint8.nhdr|--iso 64 --view 30,20 --zoom 1.3 --width 3 --fill flat --fill-color #c8d8f0"
  "nk_bonsai_ra|$data/bonsai.vti|--technique rightangle --iso 40 --view 30,10 --width 2"
  "nk_bonsai_w2|$data/bonsai.vti|--iso 40 --view 30,10 --width 2 --fill shaded --fill-color #d9c7a0"
  # Fig. 9: depth-dependent width on a close-up, lines thicker where the object comes nearer.
  "nk_hydrogen_depthlaw|$data/hydrogen_atom_128x128x128_uint8.nhdr|--iso 20 --view 60,30 --zoom 2.2 --width-near 8 --width-far 1 --fill shaded --fill-color #f0d0c0"
  # Exact silhouettes on a tone-shaded iso-surface (--fill tone: Ebert & Rheingans' tone shading,
  # then with distance blending as well).
  "nk_engine_tone|$data/engine.vti|--iso 80 --view 40,25 --width 2 --fill tone --fill-color #d9c7a0"
  "nk_bonsai_tone_distance|$data/bonsai.vti|--iso 40 --view 30,10 --width 2 --fill tone --fill-color #d9c7a0 --param k_ds=0.6,k_de=1"
  # Ebert & Rheingans: the plain lit composite (gaseous illumination, Fig. 1-2) and one picture
  # per style preset, named after the figure it mirrors (over white: the gallery's background
  # wins over fig6's own dark blue, so its distance blending fades towards white).
  "er_engine_plain|$data/engine.vti|--technique illustrate --view 40,25"
  "er_engine_fig3|$data/engine.vti|--technique illustrate --style fig3-boundary --view 40,25"
  "er_bonsai_fig4|$data/bonsai.vti|--technique illustrate --style fig4-boundary-silhouette --view 30,10"
  "er_engine_fig5|$data/engine.vti|--technique illustrate --style fig5-sketch --view 40,25"
  "er_bonsai_fig6|$data/bonsai.vti|--technique illustrate --style fig6-distance-halo --view 30,10"
  "er_engine_fig7|$data/engine.vti|--technique illustrate --style fig7-tone --view 40,25"
  # Halos alone, exact (8 taps per sample) beside the halo field (the default): the README's
  # halo row compares the two.
  "er_bonsai_halo_exact|$data/bonsai.vti|--technique illustrate --effects halo --param k_hr=6,k_ho=2 --halo-mode exact --view 30,10"
  "er_bonsai_halo_field|$data/bonsai.vti|--technique illustrate --effects halo --param k_hr=6,k_ho=2 --halo-mode field --view 30,10"
  "er_neghip_fig11|$data/neghip_64x64x64_uint8.nhdr|--technique illustrate --style fig11-gradient-silhouette --view 30,20 --zoom 1.3"
  "er_ironprot_fig15|$data/ironProt.vtk|--technique illustrate --style fig15-tone --view 30,20 --zoom 1.3"
  # Diaz & Vazquez, Fig. 1 and 5: MIP, then DEMIP with growing depth weight (black background, as
  # MIP is read); Fig. 3: the three depth estimates; Fig. 7: the three colour sphere maps.
  "dv_aneurism_mip|$data/aneurism.vti|--technique mip --window 40,255 --view 30,20 --zoom 1.4 --background black"
  "dv_aneurism_demip|$data/aneurism.vti|--technique demip --window 40,255 --view 30,20 --zoom 1.4 --background black"
  "dv_aneurism_demip_dw40|$data/aneurism.vti|--technique demip --window 40,255 --depth-weight 0.4 --view 30,20 --zoom 1.4 --background black"
  "dv_bonsai_exact|$data/bonsai.vti|--technique demip --window 40,255 --depth-weight 0.3 --view 30,10 --background black"
  "dv_bonsai_steps|$data/bonsai.vti|--technique demip --window 40,255 --depth-weight 0.3 --depth-mode steps --view 30,10 --background black"
  "dv_bonsai_entry_steps|$data/bonsai.vti|--technique demip --window 40,255 --depth-weight 0.3 --depth-mode entry-plus-steps --view 30,10 --background black"
  "dv_aneurism_red_blue|$data/aneurism.vti|--technique demip --window 40,255 --sphere-weight 0.5 --sphere-map red-blue --view 30,20 --zoom 1.4 --background black"
  "dv_aneurism_green_red|$data/aneurism.vti|--technique demip --window 40,255 --sphere-weight 0.5 --sphere-map green-red --view 30,20 --zoom 1.4 --background black"
  "dv_aneurism_green_blue|$data/aneurism.vti|--technique demip --window 40,255 --sphere-weight 0.5 --sphere-map green-blue --view 30,20 --zoom 1.4 --background black"
  # The same with a transfer function instead of the grey window (docs/tf/), as MIP and DEMIP.
  "dv_aneurism_tf_mip|$data/aneurism.vti|--technique mip --tf docs/tf/aneurism_vessels.json --view 30,20 --zoom 1.4 --background black"
  "dv_aneurism_tf_demip|$data/aneurism.vti|--technique demip --tf docs/tf/aneurism_vessels.json --depth-weight 0.3 --view 30,20 --zoom 1.4 --background black"
  # Rautek, Bruckner & Groller, Fig. 6: the cube whose density rises towards its centre (gen:cube),
  # flatness 0 (the grey shell hides the red core) and 1 (the core, of higher priority, shows);
  # Fig. 8 in spirit: the tooth's focus+context rules with the cursor on the crown's left and
  # right, where the enamel turns transparent and flat so that the dentin shows through.
  "rk_cube_fig6_flat0|gen:cube:64|--technique semantic --rules fig6-cube --flatness 0 --view 30,20"
  "rk_cube_fig6_flat1|gen:cube:64|--technique semantic --rules fig6-cube --flatness 1 --view 30,20"
  "rk_tooth_cursor_left|$data/tooth.nrrd|--technique semantic --rules tooth-focus-context --view 0,10 --zoom 1.2 --cursor 25,12,130"
  "rk_tooth_cursor_right|$data/tooth.nrrd|--technique semantic --rules tooth-focus-context --view 0,10 --zoom 1.2 --cursor 80,12,130"
  # docs/figures.md: the papers' figures side by side with stand-ins, fig_<paper>_<figure>[panel]
  # (er Ebert & Rheingans, nk Nagy & Klein, dv Diaz & Vazquez, rk Rautek et al.). Each names its
  # own background, transfer function and window, so that later changes to the defaults do not
  # change these pictures. Ebert & Rheingans' abdominal CT (256x256x128) -> the engine (the same
  # size), its MRI tomato -> neghip, its iron protein -> ironProt; all over black as in the paper.
  # docs/tf/power*.json write the paper's power opacity k_os*v^k_oe out as transfer functions.
  "fig_er_1|$data/engine.vti|--technique illustrate --tf docs/tf/engine_grey.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_2|$data/engine.vti|--technique illustrate --tf docs/tf/engine_colored.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_3|$data/engine.vti|--technique illustrate --style fig3-boundary --tf docs/tf/engine_colored.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_4|$data/engine.vti|--technique illustrate --style fig4-boundary-silhouette --tf docs/tf/engine_grey.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_5|$data/engine.vti|--technique illustrate --style fig5-sketch --sketch-color white --tf docs/tf/power3_white.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_6|$data/engine.vti|--technique illustrate --style fig6-distance-halo --param k_de=2,k_hd=8,k_ho=4,k_hr=6 --tf docs/tf/engine_colored.json --view 40,25 --zoom 1.25 --background #000026"
  "fig_er_7|$data/engine.vti|--technique illustrate --style fig7-tone --tf docs/tf/engine_grey.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_8|$data/engine.vti|--technique illustrate --effects tone --param k_ty=0.3,k_tb=0.3,k_ta=1,k_td=0.6 --tf docs/tf/engine_colored.json --view 40,25 --zoom 1.25 --background black"
  "fig_er_10|$data/neghip_64x64x64_uint8.nhdr|--technique illustrate --tf docs/tf/power2_ivory_os0.5.json --view 30,20 --zoom 1.1 --background black"
  "fig_er_11|$data/neghip_64x64x64_uint8.nhdr|--technique illustrate --style fig11-gradient-silhouette --tf docs/tf/power2_ivory_os0.03.json --view 30,20 --zoom 1.1 --background black"
  "fig_er_14|$data/ironProt.vtk|--technique illustrate --tf docs/tf/power2_ivory.json --view 30,20 --zoom 1.15 --background black"
  "fig_er_15|$data/ironProt.vtk|--technique illustrate --style fig15-tone --tf docs/tf/power2_ivory.json --view 30,20 --zoom 1.15 --background black"
  # Nagy & Klein: black lines on white; a: right-angle, b: one-pixel silhouettes, c: broadened.
  "fig_nk_3|gen:spheres:128|--view 30,20 --zoom 2 --width 2 --fill shaded --fill-color #d0d0d0 --background white"
  "fig_nk_5a|$data/engine.vti|--technique rightangle --iso 80 --view 40,25 --zoom 1.25 --width 2 --background white"
  "fig_nk_5b|$data/engine.vti|--iso 80 --view 40,25 --zoom 1.25 --width 1 --background white"
  "fig_nk_5c|$data/engine.vti|--iso 80 --view 40,25 --zoom 1.25 --width 3 --background white"
  "fig_nk_6a|$data/neghip_64x64x64_uint8.nhdr|--technique rightangle --iso 64 --view 30,20 --zoom 1.1 --width 2 --background white"
  "fig_nk_6b|$data/neghip_64x64x64_uint8.nhdr|--iso 64 --view 30,20 --zoom 1.1 --width 1 --background white"
  "fig_nk_6c|$data/neghip_64x64x64_uint8.nhdr|--iso 64 --view 30,20 --zoom 1.1 --width 3 --background white"
  "fig_nk_7a|$data/bonsai.vti|--technique rightangle --iso 40 --crop :,24:,: --view 30,10 --zoom 1.1 --width 2 --background white"
  "fig_nk_7b|$data/bonsai.vti|--iso 40 --crop :,24:,: --view 30,10 --zoom 1.1 --width 2 --background white"
  # The teddy seen from the front (the CT table cut off with --crop), then from its side.
  "fig_nk_8a|$data/teddybear_128x128x62_uint8.nhdr|--technique rightangle --iso 50 --crop :,0:90,: --view 180,-90 --zoom 1.6 --width 2 --background white"
  "fig_nk_8b|$data/teddybear_128x128x62_uint8.nhdr|--iso 50 --crop :,0:90,: --view 180,-90 --zoom 1.6 --width 2 --background white"
  "fig_nk_8c|$data/teddybear_128x128x62_uint8.nhdr|--iso 50 --crop :,0:90,: --up -z --view 270,5 --zoom 1.3 --width 2 --fill shaded --fill-color #e0d0b0 --background white"
  "fig_nk_9a|$data/hydrogen_atom_128x128x128_uint8.nhdr|--iso 20 --view 60,30 --zoom 1.6 --width-near 8 --width-far 1 --background white"
  "fig_nk_9b|$data/hydrogen_atom_128x128x128_uint8.nhdr|--iso 20 --view 60,30 --zoom 2.4 --width-near 8 --width-far 1 --background white"
  "fig_nk_9c|$data/hydrogen_atom_128x128x128_uint8.nhdr|--iso 20 --view 60,30 --zoom 3 --width-near 8 --width-far 1 --background white"
  # Diaz & Vazquez, over black with explicit windows: the thorax -> the engine, the hip -> the
  # engine from its other side, Fig. 3's model -> the bonsai, the aneurysm -> aneurism; the DVR
  # panels are illustrate with a transfer function.
  "fig_dv_1a|$data/engine.vti|--technique mip --window 60,255 --view 40,25 --zoom 1.25 --background black"
  "fig_dv_1b|$data/engine.vti|--technique demip --window 60,255 --material-eps 25.5 --depth-weight 0.3 --view 40,25 --zoom 1.25 --background black"
  "fig_dv_1c|$data/engine.vti|--technique demip --window 60,255 --material-eps 25.5 --depth-weight 0.3 --sphere-weight 0.5 --sphere-map red-blue --legend --view 40,25 --zoom 1.25 --background black"
  "fig_dv_1d|$data/engine.vti|--technique illustrate --tf docs/tf/engine_colored.json --view 40,25 --zoom 1.25 --background black"
  "fig_dv_3a|$data/bonsai.vti|--technique mip --window 40,255 --view 30,10 --zoom 1.1 --background black"
  "fig_dv_3b|$data/bonsai.vti|--technique demip --window 40,255 --depth-weight 0.3 --depth-mode entry-plus-steps --view 30,10 --zoom 1.1 --background black"
  "fig_dv_3c|$data/bonsai.vti|--technique demip --window 40,255 --depth-weight 0.3 --depth-mode steps --view 30,10 --zoom 1.1 --background black"
  "fig_dv_3d|$data/bonsai.vti|--technique demip --window 40,255 --depth-weight 0.3 --depth-mode exact --view 30,10 --zoom 1.1 --background black"
  "fig_dv_5a|$data/engine.vti|--technique demip --window 60,255 --material-eps 25.5 --depth-weight 0 --view 130,25 --zoom 1.25 --background black"
  "fig_dv_5b|$data/engine.vti|--technique demip --window 60,255 --material-eps 25.5 --depth-weight 0.15 --view 130,25 --zoom 1.25 --background black"
  "fig_dv_5c|$data/engine.vti|--technique demip --window 60,255 --material-eps 25.5 --depth-weight 0.3 --view 130,25 --zoom 1.25 --background black"
  "fig_dv_6a|$data/aneurism.vti|--technique mip --window 20,255 --view 30,20 --zoom 1.4 --background black"
  "fig_dv_6b|$data/aneurism.vti|--technique demip --window 20,255 --depth-weight 0.3 --view 30,20 --zoom 1.4 --background black"
  "fig_dv_6c|$data/aneurism.vti|--technique demip --window 20,255 --depth-weight 0.3 --sphere-weight 0.5 --sphere-map red-blue --legend --view 30,20 --zoom 1.4 --background black"
  "fig_dv_6d|$data/aneurism.vti|--technique illustrate --tf docs/tf/aneurism_vessels.json --view 30,20 --zoom 1.4 --background black"
  "fig_dv_7a|$data/aneurism.vti|--technique demip --window 20,255 --sphere-weight 0.5 --sphere-map red-blue --view 30,20 --zoom 1.4 --background black"
  "fig_dv_7b|$data/aneurism.vti|--technique demip --window 20,255 --sphere-weight 0.5 --sphere-map green-red --view 30,20 --zoom 1.4 --background black"
  "fig_dv_7c|$data/aneurism.vti|--technique demip --window 20,255 --sphere-weight 0.5 --sphere-map green-blue --view 30,20 --zoom 1.4 --background black"
  # Rautek et al.: the cube at flatness 0, 0.5, 1; a slicing plane through the tooth; the cursor.
  "fig_rk_6a|gen:cube:64|--technique semantic --rules fig6-cube --flatness 0 --view 30,20 --background white"
  "fig_rk_6b|gen:cube:64|--technique semantic --rules fig6-cube --flatness 0.5 --view 30,20 --background white"
  "fig_rk_6c|gen:cube:64|--technique semantic --rules fig6-cube --flatness 1 --view 30,20 --background white"
  "fig_rk_7|$data/tooth.nrrd|--technique semantic --rules docs/rules/fig7-tooth-plane.rules --plane 51,47,90,0,0,1 --plane-show --view 20,20 --zoom 1.2 --background white"
  "fig_rk_8a|$data/tooth.nrrd|--technique semantic --rules tooth-focus-context --cursor 25,12,130 --view 0,10 --zoom 1.2 --background white"
  "fig_rk_8b|$data/tooth.nrrd|--technique semantic --rules tooth-focus-context --cursor 80,12,130 --view 0,10 --zoom 1.2 --background white"
)

count=0
for entry in "${entries[@]}"; do
  IFS='|' read -r name input options <<<"$entry"
  [[ $name == "$prefix"* ]] || continue
  count=$((count + 1))
  echo "gallery: $name" >&2
  background="--background white"  # unless the entry names its own (MIP is read over black)
  [[ $options == *--background* ]] && background=""
  # shellcheck disable=SC2086  # options are a word list on purpose
  "$vsil" render "$input" $common $background $options --out "$out/$name.png"
done
echo "gallery: $count images in $(pwd)/$out" >&2
