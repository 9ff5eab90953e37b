#!/usr/bin/env bash
# Each bad input ends the run before the first step with status 2 and one line
# "sphfsi: error: ..." naming the problem (no PETSc banner, no MPI_ABORT, no crash).
MPI=$1; OUT=$2; MPI8=${3:-} # MPI8: the launcher for 8 ranks (run_tests.sh)
rm -f "$OUT"/verdict.*; mkdir -p "$OUT"
n=0
# The cases run three at a time (each mostly launcher and PETSc start-up), each in a directory of its
# own; a case's verdict goes to $OUT/verdict.N and they are counted at the end.
JOBS=3
spawn() { while [ "$(jobs -rp | wc -l)" -ge $JOBS ]; do wait -n; done; "$@" & }
check() { n=$((n + 1)); spawn check_one $n "$MPI" "$@"; }
fails() { n=$((n + 1)); spawn fails_one $n "$MPI" "$@"; }
check_one() { # N, launcher, expected message fragment, arguments...: status 2 and the one line "sphfsi: error: ..."
  local k=$1 mpi=$2 want=$3; shift 3
  timeout 60 $mpi bin/sphfsi -output_dir "$OUT/run$k" -overwrite -t_end 0.001 -progress_every 0 "$@" > "$OUT/case$k.log" 2>&1
  local rc=$?
  if [ $rc -ne 2 ] || [ "$(grep -c '^sphfsi: error: ' "$OUT/case$k.log")" -ne 1 ] || grep -q "PETSC ERROR\|MPI_ABORT\|Segmentation\|signal" "$OUT/case$k.log" || ! grep '^sphfsi: error: ' "$OUT/case$k.log" | grep -qi -- "$want"; then
    echo "bad input $k ($*): status $rc, expected status 2 and one line 'sphfsi: error: ...' with '$want'" > "$OUT/verdict.$k"
  fi
}
fails_one() { # N, launcher, message fragment, arguments...: a run that fails (not bad input): non-zero status and the message, no crash
  local k=$1 mpi=$2 want=$3; shift 3
  timeout 60 $mpi bin/sphfsi -output_dir "$OUT/run$k" -overwrite -t_end 0.001 -progress_every 0 "$@" > "$OUT/case$k.log" 2>&1
  local rc=$?
  if [ $rc -eq 0 ] || [ $rc -ge 124 ] || grep -q "Segmentation\|signal" "$OUT/case$k.log" || ! grep -qi -- "$want" "$OUT/case$k.log"; then
    echo "failing run $k ($*): status $rc, expected a message with '$want'" > "$OUT/verdict.$k"
  fi
}
check "No scene given"        -dx 0.01
check "Unknown -case"         -case nosuch
check "-fluid"                -case dam_break -fluid lbm
check "-dx"                   -case dam_break -dx -0.01
check "-dx"                   -case dam_break -dx 0
check "-t_end"                -case hydrostatic -t_end -1
check "larger than half"      -case hydrostatic -dx 0.2
check "-cfl"                  -case dam_break -cfl 3
check "-water_depth"          -case hydrostatic -water_depth -0.1
check "-column_width"         -case dam_break -column_width 0
check "options_file"          -options_file cases/does_not_exist.opts
check "output directory"      -case hydrostatic -dx 0.01 -output_dir /proc/forbidden
check "-rebalance_threshold"  -case dam_break -rebalance_threshold 0.5
check "-decomp_sparse_ranks"  -case dam_break -decomp_sparse_ranks 0
check "-wcsph_delta"          -case dam_break -wcsph_delta 2
check "-wcsph_delta"          -case dam_break -delta 2  # its name before 0.9.0: works on, the error names the new one
check "-wcsph_skin"           -case dam_break -wcsph_skin 3
check "-wcsph_tic is for confined flows" -case dam_break -fluid wcsph -wcsph_tic  # a free surface
check "-fluid_shift_speed"   -case dam_break -fluid wcsph -fluid_shift_speed -1
check "-wcsph_wall_av"        -case dam_break -wcsph_wall_av 2
check "-isph_wall_av"         -case dam_break -fluid isph -isph_wall_av -1
check "-wcsph_riemann"        -case dam_break -wcsph_riemann -3
check "-sensor_size"          -case dam_break_buchner -sensor_size 0.5
check "-fluid_start_jitter"   -case dam_break -fluid_start_jitter 0.5
check "-h_factor"             -case dam_break -h_factor 0.5
check "-kernel"               -case dam_break -kernel gauss
check "-isph_beta"            -case dam_break -fluid isph -isph_beta 1.5
check "-isph_source"          -case dam_break -fluid isph -isph_source magic
check "-isph_gradient_cond"   -case dam_break -fluid isph -isph_gradient_cond 1.5
# more ranks than cells that hold particles (6 here): the largest rank count that can run
[ -n "$MPI8" ] && MPI=$MPI8 check "at most 6 ranks" -case hydrostatic -dx 0.05
fails "DIVERGED_ITS"          -case hydrostatic -fluid isph -dx 0.01 -ppe_ksp_max_it 1 -ppe_ksp_error_if_not_converged
fails "DIVERGED_ITS"          -case hydrostatic -fluid isph -dx 0.01 -ppe_ksp_max_it 1
check "-solid_K"              -case oscillating_plate -solid_K -1
check "-floor_downstream"     -case elastic_gate -dx 0.00125 -floor_downstream -0.1
check "-solid_G"              -case oscillating_plate -solid_G -5
check "-solid_art_stress"     -case oscillating_plate -solid_art_stress 2
check "-solid_gradient"       -case oscillating_plate -solid_gradient magic
check "-plate_ny"             -case oscillating_plate -plate_ny 2
check "not both"              -case oscillating_plate -plate_ny 8 -dx 0.002
check "-plate_vf"             -case oscillating_plate -plate_vf 0.5
check "-clamp_columns"        -case oscillating_plate -clamp_columns 1
check "-block_motion"         -case solid_block -block_motion spin
check "-solid_cfl"            -case oscillating_plate -solid_cfl 0.4
check "-solid_order"          -case oscillating_plate -solid_order 3
check "-solid_h_factor"       -case oscillating_plate -h_factor 1.3 -solid_h_factor 1.5
check "-solid_formulation"    -case oscillating_plate -solid_formulation eulerian
# the solid's law and its moduli as K, G or E, nu (one pair)
check "-solid_law"            -case oscillating_plate -solid_law mooney_rivlin
check "needs -solid_formulation total" -case oscillating_plate -solid_law st_venant_kirchhoff -solid_formulation updated
check "not both (given: -solid_K -solid_E -solid_nu)" -case oscillating_plate -solid_K 3e6 -solid_E 2e6 -solid_nu 0.4
check "Give -solid_E and -solid_nu together" -case oscillating_plate -solid_E 2e6
check "-solid_nu 0.5 must be in (-1, 0.5)" -case oscillating_plate -solid_E 2e6 -solid_nu 0.5
check "-turek_hron_case"      -case turek_hron -turek_hron_case fsi9
check "The flag needs >= 3 particles" -case turek_hron -flag_ny 2
check "needs an even number of particles across" -case turek_hron -turek_hron_case cfd1 -flag_ny 3
check "-turek_hron_smooth and -turek_hron_ramp must be >= 0" -case turek_hron -turek_hron_case cfd3 -turek_hron_smooth -1
# issue 8: restart, malformed values, conflicts, misspelt options
timeout 60 $MPI bin/sphfsi -case hydrostatic -dx 0.01 -max_steps 2 -checkpoint_interval 1 -output_interval 1 -progress_every 0 -output_dir "$OUT/ckpt" > "$OUT/ckpt.log" 2>&1 || { echo "could not write the checkpoint the restart cases need"; exit 1; }
check "no_such_checkpoint.h5 cannot be opened (No such file"   -case hydrostatic -dx 0.01 -restart "$OUT/no_such_checkpoint.h5"
check "is not an HDF5 file"            -case hydrostatic -dx 0.01 -restart "$OUT/ckpt.log"
check "not an sphfsi checkpoint"       -case hydrostatic -dx 0.01 -restart "$OUT/ckpt/particles_00000.h5"
check "checkpoint of scene hydrostatic, not of -case dam_break" -case dam_break -restart "$OUT/ckpt/checkpoint.h5"
check "keeps the resolution"           -case hydrostatic -dx 0.005 -restart "$OUT/ckpt/checkpoint.h5"
check "restart with -fluid wcsph"      -case hydrostatic -dx 0.01 -fluid isph -restart "$OUT/ckpt/checkpoint.h5"
check "give a later -t_end"            -case hydrostatic -dx 0.01 -t_end 1e-6 -restart "$OUT/ckpt/checkpoint.h5"
check "option -dx has the value 'abc', which is not a number" -case dam_break -dx abc
check "option -max_steps has the value '1.5', which is not an integer" -case dam_break -max_steps 1.5
check "-dt_min 1e-05 and -dt 0.0001 conflict" -case dam_break -dt 1e-4 -dt_min 1e-5
check "-checkpoint_interval -1. must be >= 0" -case dam_break -checkpoint_interval -1
check "-max_wall_time -5. must be >= 0" -case dam_break -max_wall_time -5
check "-dt_min -1. must be >= 0"      -case dam_break -dt_min -1
check "not used by this run: -t_ned 1" -case dam_break -t_ned 1
check "-gravity: component 2 is not finite" -case dam_break -gravity 0,nan
check "-gravity takes 2 components in this 2D scene" -case dam_break -gravity 0,0,-9.81
check "-dim 4 must be 2 or 3" -case hydrostatic -dim 4
check "-dim 4 must be 2 or 3" -case taylor_green -dim 4
check "-dim 4 must be 2 or 3" -case oscillating_plate -dim 4
check "takes a uniform lattice"  -case elastic_gate -dim 3 -dx 0.0016667 -dx_coarse 0.0033333
check "fewer than 6 particles"   -case elastic_gate -dim 3 -dx 0.0016667 -gate_width 0.005
check "must hold >= 3 particles" -case oscillating_plate -dim 3 -plate_ny 4 -plate_width 0.01
check "not used by this run: -gate_width" -case elastic_gate -gate_width 0.02
check "-gauge_solid_1 takes 6 numbers" -case boxes -dim 3 -dx 0.005 -solid_box_1 0,0,0.1,0.2,0.02,0.12 -clamp_box_1 -0.02,0,0.1,0,0.02,0.12 -domain -0.03,-0.05,-0.2,0.25,0.07,0.25 -gauge_solid_1 0.195,0,0.2,0.02
# issue 27: bad geometry of a case given as data (-case boxes)
check "has no water"                   -case boxes -dx 0.01 -tank_1 0,1,0,1
check "-fluid_box_1 overlaps -wall_box_1" -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5,0.5 -wall_box_1 0.4,0,0.6,0.1
check "overlaps the walls of -tank_1"   -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 -0.2,0,0.5,0.5
check "-gauge_pressure_1 5.,0. is outside the domain" -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5,0.5 -gauge_pressure_1 5,0
check "-fluid_box_1 takes 4 or 5 numbers" -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5
check "needs -dx"                      -case boxes -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5,0.5
check "has no water"                   -case boxes -dim 3 -dx 0.01 -tank_1 0,1,0,1,0,1
check "-fluid_box_1 takes 6 or 7 numbers" -case boxes -dim 3 -dx 0.01 -tank_1 0,1,0,1,0,1 -fluid_box_1 0,0,0.5,0.5
check "a 3D tank has walls on all four sides" -case boxes -dim 3 -dx 0.01 -tank_1 0,1,0,1,0,1 -tank_1_sides left -fluid_box_1 0,0,0,0.5,0.5,0.5
check "-solid_box_1 touches no -clamp_box" -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5,0.5 -solid_box_1 0.6,0,0.7,0.3
# issue 48: bad shapes (-cylinder_K, -sphere_K, -polygon_K; docs/geometry.md)
check "-polygon_1: a polygon needs at least 3 vertices, not 2" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -polygon_1 0.2,0.2,0.4,0.2
check "-polygon_1: edges 1 and 3 cross or touch (edge i" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -polygon_1 0.2,0.2,0.4,0.4,0.4,0.2,0.2,0.4
check "-polygon_1: vertices 2 and 3 are the same point" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -polygon_1 0.2,0.2,0.4,0.2,0.4,0.2,0.3,0.4
check "-polygon_1: edges 1 and 3 cross or touch" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -polygon_1 0.2,0.2,0.4,0.2,0.6,0.2
check "-polygon_1 has 5 numbers: give x,y pairs" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -polygon_1 0.2,0.2,0.4,0.2,0.3
check "no_such_file.txt cannot be opened" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -polygon_1_file no_such_file.txt
check "-cylinder_1: the radius -0.1 must be > 0" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -cylinder_1 0.5,0.25,-0.1
check "-cylinder_1 takes 3 numbers x,y,r, not 2" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -cylinder_1 0.5,0.25
check "in 3D give -sphere_1"         -case boxes -dim 3 -dx 0.01 -domain 0,0,0,1,1,1 -fluid_box_1 0,0,0,1,1,0.5 -cylinder_1 0.5,0.5,0.2,0.1
check "-cylinder_1 reaches outside the domain" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -cylinder_1 0.95,0.25,0.1
check "-cylinder_1 (wall) overlaps -cylinder_2 (wall)" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -cylinder_1 0.5,0.25,0.1 -cylinder_2 0.6,0.25,0.1
check "-cylinder_1 (fluid) overlaps -fluid_box_1" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -cylinder_1 0.5,0.6,0.2 -cylinder_1_kind fluid
check "-cylinder_1 is wider than the periodic domain in x" -case boxes -dx 0.01 -domain 0,0,0.2,1 -periodic x -fluid_box_1 0,0,0.2,0.5 -cylinder_1 0.1,0.25,0.15
check "-cylinder_1_kind"             -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -cylinder_1 0.5,0.25,0.1 -cylinder_1_kind rock
# a shape sharing space with a box of walls, solid or clamp (they may touch: SPHERIC Test 2's STL box
# rests on the tank's floor)
check "-cylinder_1 (wall) overlaps the walls of -tank_1" -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5,0.5 -cylinder_1 0.5,0.01,0.03
check "-cylinder_1 (fluid) overlaps -wall_box_1" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.3 -wall_box_1 0.4,0.4,0.6,0.6 -cylinder_1 0.5,0.7,0.15 -cylinder_1_kind fluid
check "-polygon_1 (solid) overlaps -clamp_box_1" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.3 -clamp_box_1 0.4,0.4,0.5,0.6 -polygon_1 0.45,0.4,0.8,0.4,0.8,0.6,0.45,0.6 -polygon_1_kind solid
check "-periodic x needs -domain"    -case boxes -dx 0.01 -tank_1 0,1,0,1 -fluid_box_1 0,0,0.5,0.5 -periodic x
check "-periodic q: the directions are x, y" -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -periodic q
# a case file's fixed -domain with a -dx whose walls stick out of it (crashed at the first migration before)
check "outside its domain"          -options_file cases/boxes/dam_break.opts -dx 0.01
# issue 48: bad STL surfaces (-stl_K; docs/geometry.md): an open surface, a missing file, a truncated
# binary file, an ASCII facet of two vertices, an STL in 2D, a surface reaching outside the domain
B3="-case boxes -dim 3 -dx 0.05 -domain 0,0,0,1,1,1 -fluid_box_1 0,0,0,1,1,0.5"
python3 tools/stl_write.py box 0.3,0.3,0.1,0.6,0.6,0.3 "$OUT/open.stl" --open 1 > /dev/null
python3 tools/stl_write.py box 0.3,0.3,0.1,0.6,0.6,0.3 "$OUT/cube.stl" > /dev/null
head -c 500 "$OUT/cube.stl" > "$OUT/truncated.stl"
printf 'solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n  endloop\n endfacet\nendsolid x\n' > "$OUT/two.stl"
check "is not closed: 3 open edges"  $B3 -stl_1 "$OUT/open.stl"
check "no_such.stl cannot be opened" $B3 -stl_1 "$OUT/no_such.stl"
check "binary STL of 12 triangles by its header, which takes 684 bytes, but has 500" $B3 -stl_1 "$OUT/truncated.stl"
check "a facet with 2 vertices, not 3" $B3 -stl_1 "$OUT/two.stl"
check "STL surfaces are 3D"          -case boxes -dx 0.01 -domain 0,0,1,1 -fluid_box_1 0,0,1,0.5 -stl_1 "$OUT/cube.stl"
check "-stl_1 reaches outside the domain" $B3 -stl_1 "$OUT/cube.stl" -stl_1_translate 0.5,0,0
check "-stl_1 (wall) overlaps -wall_box_1" $B3 -stl_1 "$OUT/cube.stl" -stl_1_translate 0,0,0.35 -wall_box_1 0.5,0.5,0.5,0.8,0.8,0.8
# open boundaries (docs/open_boundaries.md)
check "points out of the domain"      -case open_channel -inlet_velocity -0.1
check "is thinner than the kernel's reach" -case open_channel -wall_rows 1
check "cannot read the profile table /nonexistent/profile.txt" -case open_channel -inlet_table /nonexistent/profile.txt
check "the outlet's pressure is the pressure equation's Dirichlet value 0" -case open_channel -fluid isph -outlet_pressure 100
OB="-case boxes -dx 0.01 -domain -0.03,-0.03,0.53,0.13 -fluid_box_1 -0.03,0,0.53,0.1 -wall_box_1 -0.03,-0.03,0.53,0 -wall_box_1_faces top -gravity 0,0 -fluid_c0 3"
check "overlaps open boundary 1 (inlet)"  $OB -inlet_1 -0.03,0,0,0.1 -inlet_1_velocity 0.1 -outlet_1 -0.02,0,0.01,0.1
check "overlaps a wall or a solid"        $OB -inlet_1 -0.03,-0.03,0,0.1 -inlet_1_velocity 0.1
check "must be a whole number of spacings" $OB -inlet_1 -0.025,0,0,0.1 -inlet_1_velocity 0.1
wait
cat "$OUT"/verdict.* 2>/dev/null
bad=$(ls "$OUT"/verdict.* 2>/dev/null | wc -l)
echo "bad_input: $((n - bad)) of $n bad inputs rejected with a clear message"
[ $bad -eq 0 ]
