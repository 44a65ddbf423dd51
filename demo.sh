#!/bin/sh
# The main job on the default scene: hapticd with the simulated PHANToM in real time, a scripted
# stroke across the bricks and a press, then a press into a steep V-valley, then strokes inside a
# bowl of bricks (a textured mesh), then two pens at once; each prints its summary.
# Two pens also push two balls (physics), scrape the bricks together (audio) and are drawn
# (visual) from lock-step recordings. Then physics-client next to hapticd: the pen pushes a ball out of its dimple, and
# two pens pinch a block and lift it. Then the
# pen's scrape over the bricks and a marble rolling over them, each as a WAV with its spectrogram.
# Then the texture gallery with shaded previews, frames of the default scene and of the bowl, three
# marbles rolling in the bowl (physics-client on a lock-step recording of the pen, frames of the
# combined session, and its sound on the bowl's modes), and the user studies.
# Usage: ./demo.sh [BUILD_DIR]   (make demo builds first, then calls this)
set -eu
BUILD=${1:-build}
OUT=out/demo
mkdir -p "$OUT"
TT="$BUILD/textures/texturetool"
SI="$BUILD/scenes/scene-info"

HD="$BUILD/server/hapticd"

echo "== default scene: scenes/default.yaml"
"$SI" scenes/default.yaml --texture-out "$OUT/default_surface.png"
"$TT" preview "$OUT/default_surface.png" "$OUT/default_surface_preview.png"

echo
echo "== hapticd, real time: stroke across the bricks, then a press (about 8 s)"
"$HD" --scene scenes/default.yaml --stats-json "$OUT/hapticd_default.json" --flight-dir "$OUT"

echo
echo "== hapticd, real time: a press into a 60 degree V-valley, crease handling on (about 4 s)"
"$HD" --scene scenes/vvalley.yaml --stats-json "$OUT/hapticd_vvalley.json" --flight-dir "$OUT"

echo
echo "== hapticd, real time: a bowl of bricks, a textured mesh (scenes/brick_bowl.yaml): a stroke down its inside wall,"
echo "   half a circle round it, a press (about 13 s)"
"$HD" --scene scenes/brick_bowl.yaml --stats-json "$OUT/hapticd_brick_bowl.json" --flight-dir "$OUT"

echo
echo "== hapticd, real time: two simulated pens on the bricks under one servo clock (scenes/two_pens.yaml):"
echo "   one strokes the lower courses while the other presses, then strokes the upper ones (about 5 s)"
"$HD" --scene scenes/two_pens.yaml --stats-json "$OUT/hapticd_two_pens.json" --flight-dir "$OUT"

echo
echo "== physics: hapticd + physics-client, the simulated pen pushes a ball out of its dimple (about 6 s)"
PC="$BUILD/clients/physics_client/physics-client"
"$PC" --scene scenes/pen_pushes_ball_dimples.yaml --duration 5.5 --json "$OUT/physics_push.json" \
  --quiet > "$OUT/physics_push.txt" 2>&1 &
PC_PID=$!
sleep 0.5
"$HD" --scene scenes/pen_pushes_ball_dimples.yaml --quiet --stats-json "$OUT/hapticd_push.json" \
  --flight-dir "$OUT" > /dev/null
wait "$PC_PID" || echo "physics-client failed (see $OUT/physics_push.txt)"
cat "$OUT/physics_push.txt"

echo
echo "== physics: two pens, each pushing its own ball out of its dimple (scenes/two_pens_two_balls.yaml): hapticd"
echo "   records both pens in lock-step, physics-client simulates a pen per device on that recording"
"$HD" --scene scenes/two_pens_two_balls.yaml --lockstep --no-lcm --no-mlock --record "$OUT/two_pens_two_balls_session.lcm" \
  --quiet > /dev/null
"$PC" --scene scenes/two_pens_two_balls.yaml --replay-log "$OUT/two_pens_two_balls_session.lcm" \
  --record "$OUT/two_pens_two_balls.lcm" --no-lcm --quiet --json "$OUT/two_pens_two_balls.json"

echo
echo "== physics: two pens pinch a wooden block and lift it by friction (scenes/two_pens_pinch.yaml, about 8 s): hapticd"
echo "   in real time with two simulated hands pushing their pens against the block's sides, physics-client with grasping"
echo "   pens (--pen-coupling 300: each pen a body on a spring to its device's tip; the devices feel the squeeze)"
PS=scenes/two_pens_pinch.yaml
"$PC" --scene "$PS" --pen-coupling 300 --duration 7 --json "$OUT/pinch.json" --poses-csv "$OUT/pinch_poses.csv" \
  --quiet > "$OUT/pinch.txt" 2>&1 &
PC_PID=$!
sleep 0.5
"$HD" --scene "$PS" --quiet --stats-json "$OUT/hapticd_pinch.json" --flight-dir "$OUT" > /dev/null
wait "$PC_PID" || echo "physics-client failed (see $OUT/pinch.txt)"
cat "$OUT/pinch.txt"
echo "the block's height over time: $OUT/pinch_poses.csv"

echo
echo "== audio: the pen scraping the bricks, rendered offline from a lock-step recording of the default scene (2-10 s, the most the first time, when the slab's and the pen's modes are solved)"
AC="$BUILD/clients/audio/audio-client"
WS="$BUILD/clients/audio/wav-spectrogram"
"$HD" --scene scenes/default.yaml --lockstep --no-lcm --record "$OUT/default_session.lcm" --quiet > /dev/null
"$AC" --scene scenes/default.yaml --replay-log "$OUT/default_session.lcm" --wav "$OUT/pen_scrape.wav"
"$WS" "$OUT/pen_scrape.wav" "$OUT/pen_scrape_spectrogram.png" --title "pen scraping the bricks (scenes/default.yaml)"
echo "sound: $OUT/pen_scrape.wav, its spectrogram: $OUT/pen_scrape_spectrogram.png"

echo
echo "== audio: two pens scraping the bricks at once, mixed (scenes/two_pens.yaml; 1-5 s): hapticd records both in lock-step,"
echo "   audio-client renders every pen's scrape on the slab's modes and each pen's own"
"$HD" --scene scenes/two_pens.yaml --lockstep --no-lcm --record "$OUT/two_pens_session.lcm" --quiet > /dev/null
"$AC" --scene scenes/two_pens.yaml --replay-log "$OUT/two_pens_session.lcm" --wav "$OUT/two_pens.wav"
"$WS" "$OUT/two_pens.wav" "$OUT/two_pens_spectrogram.png" --title "two pens scraping the bricks at once, mixed (scenes/two_pens.yaml)"
echo "sound: $OUT/two_pens.wav, its spectrogram: $OUT/two_pens_spectrogram.png"

echo
echo "== audio: a glass marble rolling over the bricks' bed joints (scenes/marble_rolling_bricks.yaml; 1-3 s)"
echo "   hapticd records 1.5 s in lock-step (pen held off the surface), physics-client adds its streams on the same clock,"
echo "   audio-client renders the combined session: the marble's impacts and texel path on the slab's modes"
MS=scenes/marble_rolling_bricks.yaml
"$HD" --scene "$MS" --lockstep --no-lcm --duration 1.5 --record "$OUT/marble_session.lcm" --quiet > /dev/null
"$PC" --scene "$MS" --replay-log "$OUT/marble_session.lcm" --record "$OUT/marble_combined.lcm" --no-lcm --quiet > /dev/null
"$AC" --scene "$MS" --replay-log "$OUT/marble_combined.lcm" --wav "$OUT/marble_bricks.wav"
"$WS" "$OUT/marble_bricks.wav" "$OUT/marble_bricks_spectrogram.png" --title "glass marble rolling over the bricks (scenes/marble_rolling_bricks.yaml)"
echo "sound: $OUT/marble_bricks.wav, its spectrogram: $OUT/marble_bricks_spectrogram.png"

echo
echo "== texture gallery (512^2, seed 1) -> $OUT/"
n=0
for kind in bricks vvalley grooves pebbles wood sine dimples tilted zigzag porcelain metal stone ceramic_tile; do
  n=$((n + 1))
  printf "[%d/13] %-12s " "$n" "$kind"
  "$TT" generate "$kind" --size 512 --out "$OUT/$kind.png" | head -n 1
  "$TT" preview "$OUT/$kind.png" "$OUT/${kind}_preview.png" > /dev/null
done

echo
echo "== visual: the default scene headless, relief mapping, 4 frames around it -> $OUT/visual/"
VC="$BUILD/clients/visual/visual-client"
LP_NUM_THREADS=${LP_NUM_THREADS:-2} "$VC" --scene scenes/default.yaml --mode relief --frames 4 --out "$OUT/visual" --quiet \
  && echo "frames: $OUT/visual/frame_0000.png ... frame_0003.png" || echo "visual-client failed"

echo
echo "== visual: the bowl of bricks, relief mapping in the mesh's tangent frames: 4 frames around it, then the pen's"
echo "   recorded strokes one frame per second (a lock-step recording of the scene) -> $OUT/visual_bowl/, $OUT/visual_bowl_pen/"
"$HD" --scene scenes/brick_bowl.yaml --lockstep --no-lcm --record "$OUT/bowl_session.lcm" --quiet > /dev/null
LP_NUM_THREADS=${LP_NUM_THREADS:-2} "$VC" --scene scenes/brick_bowl.yaml --mode relief --frames 4 --out "$OUT/visual_bowl" --quiet \
  && LP_NUM_THREADS=${LP_NUM_THREADS:-2} "$VC" --scene scenes/brick_bowl.yaml --mode relief --replay-log "$OUT/bowl_session.lcm" \
    --rate 1 --out "$OUT/visual_bowl_pen" --quiet \
  && echo "frames: $OUT/visual_bowl/frame_0000.png ... frame_0003.png, $OUT/visual_bowl_pen/frame_*.png" || echo "visual-client failed"

echo
echo "== visual: the two pens on the bricks (the audio step's lock-step recording of scenes/two_pens.yaml), every pen"
echo "   in its own colour (left red/yellow, right blue/cyan), a frame every half second -> $OUT/visual_two_pens/"
LP_NUM_THREADS=${LP_NUM_THREADS:-2} "$VC" --scene scenes/two_pens.yaml --replay-log "$OUT/two_pens_session.lcm" \
    --rate 2 --elevation 70 --distance 0.16 --out "$OUT/visual_two_pens" --quiet \
  && echo "frames: $OUT/visual_two_pens/frame_*.png" || echo "visual-client failed"

# A physics scene offline, as a user would run it by hand: hapticd's simulated pen recorded in
# lock-step, physics-client on that recording, relief frames every half second of the combined
# session, and its sound with a spectrogram. Arguments: the scene's name, the summary lines to
# show (a regular expression), the spectrogram's title.
physics_scene_offline() {
  local name=$1 lines=$2 title=$3 scene=scenes/$1.yaml
  "$HD" --scene "$scene" --lockstep --no-lcm --record "$OUT/${name}_pen.lcm" --quiet > /dev/null
  "$PC" --scene "$scene" --replay-log "$OUT/${name}_pen.lcm" --record "$OUT/${name}_session.lcm" \
    --quiet > "$OUT/$name.txt" 2>&1 && grep -E "$lines" "$OUT/$name.txt" || echo "physics-client failed"
  LP_NUM_THREADS=${LP_NUM_THREADS:-2} "$VC" --scene "$scene" --mode relief --replay-log "$OUT/${name}_session.lcm" \
    --rate 2 --out "$OUT/visual_$name" --quiet \
    && echo "frames: $OUT/visual_$name/frame_*.png" || echo "visual-client failed"
  "$AC" --scene "$scene" --replay-log "$OUT/${name}_session.lcm" --wav "$OUT/$name.wav" > "$OUT/${name}_audio.txt" 2>&1 \
    && "$WS" "$OUT/$name.wav" "$OUT/${name}_spectrogram.png" --title "$title ($scene)" \
    && echo "sound: $OUT/$name.wav, its spectrogram: $OUT/${name}_spectrogram.png" || echo "audio-client failed"
}

echo
echo "== physics on a mesh: three marbles roll down the bowl of bricks and the pen strokes through them"
echo "   (scenes/marble_bowl.yaml): the pen recorded in lock-step, physics-client on that recording, one frame"
echo "   every half second of the combined session -> $OUT/visual_marble_bowl/, and heard: the bowl's own modes (the"
echo "   solid its mesh encloses, Gmsh; about 10 s the first time) struck where the marbles and the pen touch it, and"
echo "   where the pen scrapes it"
physics_scene_offline marble_bowl "^  (red|green|blue) " "marbles in the bowl of bricks"

echo
echo "== textured marbles on a textured curved surface: the same bowl with two bump-mapped marbles (sine bumps, dimples)"
echo "   and a plain one (scenes/bumpy_marbles_bowl.yaml), both textures in each textured marble's contact (but by the"
echo "   floor's centre, where the bricks squeeze to a point); they roll down, meet on the floor, and the pen strokes"
echo "   through them. Recorded in lock-step, physics-client on the recording,"
echo "   frames every half second -> $OUT/visual_bumpy_marbles_bowl/, and heard"
physics_scene_offline bumpy_marbles_bowl "^  (bumps|dimples|plain) " "bumpy marbles in the bowl of bricks"

echo
echo "== textured objects: a grooved block on a grooved plane (scenes/grooved_block.yaml), both reliefs in the contact:"
echo "   the pen pushes it along the grooves (it slides, staying in them), then across (it climbs from groove to groove);"
echo "   recorded in lock-step, physics-client on the recording, frames every half second -> $OUT/visual_grooved_block/, and heard"
physics_scene_offline grooved_block "^  block " "a grooved block pushed on a grooved plane"

echo
echo "== a textured ball: a dimpled ball on the grooved plane (scenes/dimpled_ball_grooves.yaml), its bump map and the plane's"
echo "   relief both in the contact; the pen pushes it along the grooves, then across them (it rolls over their rims);"
echo "   recorded in lock-step, physics-client on the recording, frames every half second -> $OUT/visual_dimpled_ball_grooves/, and heard"
physics_scene_offline dimpled_ball_grooves "^  ball " "a dimpled ball pushed on a grooved plane"

echo
echo "== a textured object on a textured curved surface: a grooved block in the bowl of bricks (scenes/grooved_block_bowl.yaml),"
echo "   both reliefs in the contact on the bowl's chart under it; the pen pushes it across the floor. The pen recorded"
echo "   in lock-step, physics-client on the recording, frames every half second -> $OUT/visual_grooved_block_bowl/, and heard"
physics_scene_offline grooved_block_bowl "^  block " "a grooved block pushed in the bowl of bricks"

echo
echo "== user studies: three simulated participants per study on the shipped surfaces (scenes/study/), then the analysis -> $OUT/study/ (about 30 s)"
SR="$BUILD/clients/study/study-run"
mkdir -p "$OUT/study"
rm -f "$OUT"/study/*.csv
for p in 1 2 3; do
  for m in identification relief_vs_normal; do
    "$SR" --manifest "scenes/study/$m.yaml" --participant "S0$p" --seed "$p" --simulate \
      --out "$OUT/study/S0${p}_$m.csv" > /dev/null || echo "study-run failed ($m, participant S0$p)"
  done
done
"$BUILD/clients/study/study-analyze" --out "$OUT/study" "$OUT"/study/*.csv > /dev/null \
  && echo "sessions: $OUT/study/*.csv; tables and plots: $OUT/study/study.md" || echo "study-analyze failed"

echo
echo "Statistics: $OUT/hapticd_*.json. Pictures: $OUT/*_preview.png, $OUT/visual/*.png, $OUT/visual_bowl*/*.png, $OUT/visual_two_pens/*.png, $OUT/visual_marble_bowl/*.png, $OUT/visual_bumpy_marbles_bowl/*.png, $OUT/visual_grooved_block/*.png, $OUT/visual_grooved_block_bowl/*.png. Sounds: $OUT/*.wav, their spectrograms $OUT/*_spectrogram.png."
