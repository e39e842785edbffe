#!/bin/sh
# The catalogue of bad inputs (tests/bad_inputs/): each case file stops the set-up with its exact
# message (file, line, key or value) and exit code 2 (3 for i/o), and nothing crashes. Also a
# missing or unreadable case file, an output folder that cannot be written, and the particle limit.
# usage: test_bad_inputs.sh RYUSHI SOURCE_DIR
set -u
RY=$1
SRC=$2
D="$SRC/tests/bad_inputs"
. "$SRC/tests/cli/lib.sh"

# case NAME CODE TEXT: tests/bad_inputs/NAME.yaml through `ryushi run` (nothing may be written)
case_() {
    expect_text "$2" "$D/$1.yaml$3" "$RY" run "$D/$1.yaml" -o "$T/out_$1"
    [ -e "$T/out_$1" ] && bad "$1: an output folder was created"
}

case_ unknown_key 2 ":6: unknown key 'time.cfll' (did you mean 'time.cfl'?)"
case_ wrong_type 2 ":2: key 'spacing': expected a positive number, got 'abc'"
case_ negative_spacing 2 ":2: key 'spacing': expected a positive number, got '-0.01'"
case_ dimension_4 2 ":1: key 'dimension': expected an integer in [2, 3], got '4'"
case_ kernel_h_out_of_range 2 ":7: key 'kernel.h_over_dx': expected a number in [0.5, 4], got '9'"
case_ kernel_unknown 2 ":7: key 'kernel.type': expected one of cubic, quintic, wendland_c2, wendland_c4, lucy, gaussian; got 'cubik'"
case_ pair_loop_cells_tvf 2 ":7: key 'scheme.pair_loop': 'cells' needs no transport_velocity"
case_ cfl_out_of_range 2 ":6: key 'time.cfl': expected a number in [0.001, 1], got '2'"
case_ dt_max_negative 2 ":6: key 'time.dt_max': expected a number >= 0, got '-0.001'"
case_ end_time_zero 2 ":6: key 'time.end': expected a positive number, got '0'"
case_ domain_inverted 2 ":7: key 'domain.hi': must exceed domain.lo in every direction"
case_ particles_outside_domain 2 ":7: key 'domain': particle 5 of body at (0.055, 0.005) lies outside the domain"
case_ overlapping_bodies 2 ":6: body 'bodies[1]' overlaps body 'bodies[0]': its particle at (0.045, 0.035) lies within half a spacing of one of that body's particles"
case_ empty_body 2 ":4: body 'bodies[0]': holds no particle at spacing 0.01 (too small or inverted)"
case_ box_inverted 2 ":4: body 'bodies[0]': box: hi must exceed lo in every direction"
case_ box_wave_too_high 2 ":4: body 'bodies[0]': box: top_amplitude must be smaller than the box height"
case_ missing_scheme 2 ": key 'scheme.name': required key is missing"
case_ no_bodies 2 ": key 'bodies': at least one body is required"
case_ syntax_error 2 ":4: syntax error: mismatched flow mapping end"
case_ duplicate_key 2 ":7: key 'spacing': duplicate key (first given on line 2)"
case_ yaml_directive 2 ":2: YAML directives (lines starting with '%') are not supported"
case_ alias 2 ":2: anchors and aliases are not supported"
case_ contact_angle_without_model 2 ":7: key 'surface_tension.contact_angle': needs a surface_tension.model"
case_ wall_layers_negative 2 ":5: key 'domain.wall_layers': expected an integer in [0, 100], got '-1'"
case_ preconditioner_unknown 2 ":5: key 'scheme.solver.preconditioner': expected one of jacobi, boomeramg; got 'amg'"
case_ deflation_with_boomeramg 2 ":7: key 'scheme.solver.deflation': goes with the jacobi preconditioner only (boomeramg already solves the smooth error that deflation removes)"
case_ symmetry_unknown_face 2 ":5: key 'domain.symmetry[0]': expected one of x_lo, x_hi, y_lo, y_hi, z_lo, z_hi; got 'x_low'"
case_ symmetry_z_in_2d 2 ":5: key 'domain.symmetry[1]': 'z_lo' is beyond the case's dimension"
case_ symmetry_two_on_one_axis 2 ":5: key 'domain.symmetry[1]': 'x_hi' is a second plane across the same axis (one per axis)"
case_ symmetry_periodic 2 ":5: key 'domain.symmetry[0]': 'x_lo' is a face of a periodic direction"
case_ symmetry_particle_on_plane 2 ":5: key 'domain.symmetry': particle 4 lies within a quarter spacing of the plane x = 0.044, where its mirror image would coincide with it"
case_ symmetry_viscous_boomeramg 2 ":6: key 'scheme.viscosity_preconditioner': boomeramg runs without symmetry planes so far (domain.symmetry): jacobi"
case_ contact_angle_per_liquid_csf 2 ":6: key 'materials[0].contact_angle': a contact angle per liquid needs surface_tension.model potential (CSF takes one angle, surface_tension.contact_angle)"
case_ contact_angle_fluid_body 2 ":8: key 'bodies[0].contact_angle': applies to a body of kind wall"
case_ contact_angle_too_many_sets 2 ":13: key 'bodies[8].contact_angle': at most 7 different sets of contact angles on wall bodies"
case_ thin_fluid_body 2 ":8: key 'bodies[0].thin': applies to a body of kind wall"
case_ measure_injected_kept_one_material 2 ":6: key 'measure[1]': measurement 'injected_kept' needs two materials (the second is the injected one)"
case_ measure_polymer_stress_newtonian 2 ":7: key 'measure[1]': measurement 'max_polymer_stress' needs a visco-elastic material (rheology model oldroyd_b or giesekus)"
case_ measure_droplet_without_section 2 ":8: key 'measure[1]': the droplet measurements need the case section 'droplet' (material, tip)"
case_ stop_when_not_measured 2 ":9: key 'time.stop_when.quantity': 'front_x' is not measured (add it to 'measure')"
case_ stop_when_no_bound 2 ":9: key 'time.stop_when' needs one of 'above' and 'below'"
case_ iisph_surface_threshold_potential 2 ":9: key 'surface_tension.surface_threshold': applies to model csf with csf_form: pressure only"
case_ iisph_repulsion_out_of_range 2 ":7: key 'scheme.repulsion.distance': expected a number in [0, 1], got '2'"
case_ interfacial_sigma_one_material 2 ":9: key 'surface_tension.interfacial_sigma': needs two fluid materials"
case_ droplet_unknown_material 2 ":7: key 'droplet.material': no material named 'embolic'"
case_ mps_outlet_pressure 2 ":8: key 'open_boundaries[0].pressure': scheme mps takes outlets at pressure 0 only (its outlets remove the fluid at the downstream face, a free surface)"
case_ mps_surface_pressure_unknown 2 ":7: key 'scheme.surface_pressure': expected one of zero, hydrostatic; got 'extrapolated'"
case_ mps_deflation_negative 2 ":7: key 'scheme.solver.deflation': expected an integer in [0, 1000], got '-2'"
case_ mps_thin_wall_layers 2 ":5: key 'scheme.thin_wall_layers': expected an integer in [1, 3], got '4'"
case_ mps_thin_wall_pressure_unknown 2 ":7: key 'scheme.thin_wall_pressure': expected one of unknown, neumann; got 'dirichlet'"
case_ mps_wall_pressure_without_extrapolation 2 ":8: key 'scheme.wall_extrapolation': false leaves the walls without a pressure with scheme.wall_pressure: neumann (their pressure is the extrapolated one)"
case_ mps_contact_line_slip_not_bool 2 ":7: key 'scheme.contact_line_slip': expected true or false, got 'sometimes'"
case_ iisph_line_force_without_angle 2 ":8: key 'scheme.contact_line_force': needs scheme.contact_angle"
case_ inlet_flow_rate_and_velocity 2 ":8: key 'open_boundaries[0].flow_rate': an open boundary takes 'velocity' or 'flow_rate' with 'direction', not both"
case_ outlet_pressure_and_flow_rate 2 ":8: key 'open_boundaries[0].pressure': an outlet takes 'pressure', or 'flow_rate' or 'velocity' (a rate outlet), not both"
case_ wcsph_rate_outlet 2 ":7: key 'open_boundaries[0].type': scheme wcsph takes no rate outlets (flow_rate or velocity); use an outlet at a pressure, or scheme iisph"
case_ iisph_light_phase_surface_tension 2 ":7: key 'surface_tension.model': not available with a light phase (material 'air' is lighter than 0.05 of the heaviest, and scheme.light_phase is boundary); set scheme.light_phase: coupled"
case_ iisph_light_phase_pocket 2 ":12: key 'scheme.light_phase': 32 particles of the light material 'air' around (0.0425, 0.0275, 0) lie wholly inside the heavy fluid, a pocket the light phase does not hold (the heavy phase fills it; docs/reference/iisph.md, \"A light phase\")"
case_ mps_rate_outlet 2 ":7: key 'open_boundaries[0].type': scheme mps takes no rate outlets (flow_rate or velocity): its outlets are sinks at pressure 0"
case_ inlet_flow_rate_direction 2 ":8: key 'open_boundaries[0].direction': the flow must be along one axis (a unit vector such as [0, 0, -1])"
case_ rheology_no_bound 2 ":6: key 'materials[0].rheology.viscosity_max': required key is missing"
case_ rheology_with_viscosity 2 ":6: key 'materials[0].viscosity': not used with rheology.model carreau (the viscosity follows from the shear rate)"
case_ rheology_solid 2 ":8: key 'materials[0].rheology.model': oldroyd_b is available with schemes wcsph, iisph, mps (this case uses solid)"
case_ rheology_iisph_projected 2 ": key 'scheme.viscous_form': material 'gel' (power_law) needs morris"
case_ rheology_wcsph_inviscid 2 ":12: key 'scheme.laminar_viscosity': a non-Newtonian material needs it true"
case_ rheology_giesekus_mobility 2 ":11: key 'materials[0].rheology.mobility': expected a number in [0, 0.5], got '0.7'"
case_ iisph_curvature_smoothing 2 ":11: key 'scheme.curvature_smoothing': expected an integer in [0, 20], got '30'"
case_ gravity_length 2 ":7: key 'gravity': expected a sequence of 2 numbers, got 3 elements"
case_ unknown_material 2 ":4: key 'bodies[0].material': expected one of water; got 'oil'"
case_ materials_missing_density 2 ":3: key 'materials[0].density': required key is missing"
case_ top_level_sequence 2 ":1: the top level must be a mapping of keys, got a sequence"
case_ empty_case 2 ": key 'dimension': required key is missing"
case_ stl_in_2d 2 ":4: key 'bodies[0].type': an STL body needs dimension 3"
case_ stl_bad_fill 2 ":7: key 'bodies[0].fill': expected one of volume, surface; got 'shell'"
case_ stl_layers_without_surface 2 ":7: key 'bodies[0].layers': layers needs fill: surface"
case_ stl_negative_scale 2 ":7: key 'bodies[0].scale': expected a positive number, got '-1'"
case_ stl_not_closed 2 ":7: body 'bodies[0]': $D/geometry/open.stl:2: the surface is not closed: the edge from (0, 1, 0) to (1, 0, 0) belongs to no other triangle"
case_ stl_malformed 2 ":7: body 'bodies[0]': $D/geometry/malformed.stl:13: expected a number (vertex z), got 'x1'"
case_ stl_truncated_binary 2 ":7: body 'bodies[0]': $D/geometry/truncated.stl: binary STL: the header (byte 80) gives 4 triangles, which need 84 + 50 x 4 = 284 bytes, but the file has 200 bytes (truncated, or not an STL file)"
case_ stl_too_fine 2 ":7: body 'bodies[0]': $D/geometry/closed.stl: the surface's bounding box holds 1000000000000 lattice points at spacing 0.1"
case_ stl_missing_file 3 ":7: body 'bodies[0]': cannot read '$D/geometry/no_such_file.stl': No such file or directory"

# Every file of the catalogue is listed above.
for f in "$D"/*.yaml; do
    n=$(basename "$f" .yaml)
    grep -q "^case_ $n " "$0" || bad "$n.yaml has no expected message in $0"
done

# Files: a missing case, a folder as the case, an output folder below a regular file (i/o: 3).
expect_text 3 "cannot read '$T/missing.yaml': No such file or directory" "$RY" run "$T/missing.yaml"
expect_text 3 "cannot read '$D'" "$RY" info "$D"
: > "$T/plain_file"
expect_text 3 "i/o error" "$RY" run "$SRC/cases/dam_break_seed.yaml" -o "$T/plain_file/out" \
    --set time.end=0.001
# The particle limit: a clean error naming the body, exit code 2.
expect_text 2 "dam_break_seed.yaml:17: body 'bodies[0]': more than 1000 particles (the particle limit)" \
    env RY_MAX_PARTICLES=1000 "$RY" info "$SRC/cases/dam_break_seed.yaml"
expect_text 2 "RY_MAX_PARTICLES: expected a positive whole number, got 'lots'" \
    env RY_MAX_PARTICLES=lots "$RY" info "$SRC/cases/dam_break_seed.yaml"

finish
