/* SPDX-License-Identifier: BSD-2-Clause */
/* The sources' external names, prefixed like the FMI functions when the FMU
 * is compiled with FMI2_FUNCTION_PREFIX or FMI3_FUNCTION_PREFIX (e.g.
 * -DFMI2_FUNCTION_PREFIX=PainleveRod_):
 * so the sources can be linked statically into one program beside another
 * FMU, or beside a copy of themselves with another prefix. Every function or
 * object that one source file gives another is listed here
 * (tests/fmu/test_source_fmu.py checks that the prefixed build exports no other). */
#ifndef NAMESPACE_H
#define NAMESPACE_H

#if defined(FMI2_FUNCTION_PREFIX)
#define NAMESPACE_PREFIX FMI2_FUNCTION_PREFIX
#elif defined(FMI3_FUNCTION_PREFIX)
#define NAMESPACE_PREFIX FMI3_FUNCTION_PREFIX
#endif

#ifdef NAMESPACE_PREFIX
#define NAMESPACE_PASTE_(a, b) a##b
#define NAMESPACE_PASTE(a, b) NAMESPACE_PASTE_(a, b)
#define NAMESPACED(name) NAMESPACE_PASTE(NAMESPACE_PREFIX, name)

/* contact.c, contact_events.c, contact_record.c: the contact core over a body */
#define contact_body NAMESPACED(contact_body)
#define contact_gap_rows NAMESPACED(contact_gap_rows)
#define contact_nx NAMESPACED(contact_nx)
#define contact_coeffs NAMESPACED(contact_coeffs)
#define contact_compliance NAMESPACED(contact_compliance)
#define contact_decide_mode NAMESPACED(contact_decide_mode)
#define contact_derivatives NAMESPACED(contact_derivatives)
#define contact_energy NAMESPACED(contact_energy)
#define contact_event_indicators NAMESPACED(contact_event_indicators)
#define contact_event_update NAMESPACED(contact_event_update)
#define contact_fast_growth NAMESPACED(contact_fast_growth)
#define contact_friction_force NAMESPACED(contact_friction_force)
#define contact_indicator_name NAMESPACED(contact_indicator_name)
#define contact_indicator_noise NAMESPACED(contact_indicator_noise)
#define contact_initial_mode NAMESPACED(contact_initial_mode)
#define contact_jacobian_differences NAMESPACED(contact_jacobian_differences)
#define contact_move_off_surfaces NAMESPACED(contact_move_off_surfaces)
#define contact_normal_force NAMESPACED(contact_normal_force)
#define contact_record_describe_start NAMESPACED(contact_record_describe_start)
#define contact_record_event NAMESPACED(contact_record_event)
#define contact_record_implausible NAMESPACED(contact_record_implausible)
#define contact_record_new NAMESPACED(contact_record_new)
#define contact_record_start NAMESPACED(contact_record_start)
#define contact_spring_energy NAMESPACED(contact_spring_energy)
#define contact_surfaces_of NAMESPACED(contact_surfaces_of)
#define contact_time_scale NAMESPACED(contact_time_scale)

/* rod.c, rod_partials.c: the rod, the core's first body */
#define rod_anchor NAMESPACED(rod_anchor)
#define rod_coefficient_outputs NAMESPACED(rod_coefficient_outputs)
#define rod_coeffs NAMESPACED(rod_coeffs)
#define rod_contact NAMESPACED(rod_contact)
#define rod_flight NAMESPACED(rod_flight)
#define rod_flight_at NAMESPACED(rod_flight_at)
#define rod_flight_sample_step NAMESPACED(rod_flight_sample_step)
#define rod_jacobian NAMESPACED(rod_jacobian)
#define rod_partials NAMESPACED(rod_partials)

/* fmu_src/models/TwoLinkArm/arm_body.c: the arm, the core's second body */
#define arm_body NAMESPACED(arm_body)
#define arm_mass_matrix NAMESPACED(arm_mass_matrix)
#define arm_set_reference NAMESPACED(arm_set_reference)

/* fmu_src/models/PainleveRodSI/rod_si_partials.c */
#define si_partial NAMESPACED(si_partial)

/* model.h: the model interface (model_common.c and each model's own files) */
#define model_assign NAMESPACED(model_assign)
#define model_begin_integration NAMESPACED(model_begin_integration)
#define model_calculated_partial NAMESPACED(model_calculated_partial)
#define model_check NAMESPACED(model_check)
#define model_check_rules NAMESPACED(model_check_rules)
#define model_decide_initial_mode NAMESPACED(model_decide_initial_mode)
#define model_derivatives_at NAMESPACED(model_derivatives_at)
#define model_event_update NAMESPACED(model_event_update)
#define model_fields NAMESPACED(model_fields)
#define model_get NAMESPACED(model_get)
#define model_get_derivatives NAMESPACED(model_get_derivatives)
#define model_get_indicators NAMESPACED(model_get_indicators)
#define model_flight_at NAMESPACED(model_flight_at)
#define model_flight_begin NAMESPACED(model_flight_begin)
#define model_flight_sample_step NAMESPACED(model_flight_sample_step)
#define model_gap_rows_at NAMESPACED(model_gap_rows_at)
#define model_step_anchor NAMESPACED(model_step_anchor)
#define model_anchor NAMESPACED(model_anchor)
#define model_get_nominals NAMESPACED(model_get_nominals)
#define model_get_states NAMESPACED(model_get_states)
#define model_implausible NAMESPACED(model_implausible)
#define model_internals_implausible NAMESPACED(model_internals_implausible)
#define model_input_set NAMESPACED(model_input_set)
#define model_indicators_at NAMESPACED(model_indicators_at)
#define model_jacobian_at NAMESPACED(model_jacobian_at)
#define model_n_fields NAMESPACED(model_n_fields)
#define model_partial_derivative NAMESPACED(model_partial_derivative)
#define model_reset NAMESPACED(model_reset)
#define model_restore NAMESPACED(model_restore)
#define model_set NAMESPACED(model_set)
#define model_set_states NAMESPACED(model_set_states)
#define model_set_time NAMESPACED(model_set_time)
#define model_settable NAMESPACED(model_settable)
#define model_start NAMESPACED(model_start)
#define model_state_vr NAMESPACED(model_state_vr)
#define model_step_begin NAMESPACED(model_step_begin)
#define model_step_end NAMESPACED(model_step_end)
#define model_stored NAMESPACED(model_stored)
#define model_update NAMESPACED(model_update)
#define model_variable NAMESPACED(model_variable)

/* instance.c, instance_state.c, instance_step.c: the instance under any FMI version */
#define instance_check_set NAMESPACED(instance_check_set)
#define instance_set NAMESPACED(instance_set)
#define instance_derivatives NAMESPACED(instance_derivatives)
#define instance_discard NAMESPACED(instance_discard)
#define instance_choose_integrator NAMESPACED(instance_choose_integrator)
#define instance_event_update NAMESPACED(instance_event_update)
#define instance_fail NAMESPACED(instance_fail)
#define instance_free_solver NAMESPACED(instance_free_solver)
#define instance_get NAMESPACED(instance_get)
#define instance_log_categories NAMESPACED(instance_log_categories)
#define instance_log_event NAMESPACED(instance_log_event)
#define instance_log_statistics NAMESPACED(instance_log_statistics)
#define instance_logs_statistics NAMESPACED(instance_logs_statistics)
#define instance_model NAMESPACED(instance_model)
#define instance_read_array NAMESPACED(instance_read_array)
#define instance_reset NAMESPACED(instance_reset)
#define instance_set_logging NAMESPACED(instance_set_logging)
#define instance_set_states NAMESPACED(instance_set_states)
#define instance_set_tolerance NAMESPACED(instance_set_tolerance)
#define instance_snapshot_deserialize NAMESPACED(instance_snapshot_deserialize)
#define instance_snapshot_restore NAMESPACED(instance_snapshot_restore)
#define instance_snapshot_serialize NAMESPACED(instance_snapshot_serialize)
#define instance_snapshot_size NAMESPACED(instance_snapshot_size)
#define instance_snapshot_take NAMESPACED(instance_snapshot_take)
#define instance_start NAMESPACED(instance_start)
#define instance_step NAMESPACED(instance_step)
#define instance_state_name NAMESPACED(instance_state_name)

/* explicit_rk.c, closed_flight.c: Co-Simulation's explicit pair and closed-form flight */
#define erk_advance NAMESPACED(erk_advance)
#define erk_any_crossed NAMESPACED(erk_any_crossed)
#define erk_flight_advance NAMESPACED(erk_flight_advance)
#define erk_hand_over NAMESPACED(erk_hand_over)
#define erk_all_finite NAMESPACED(erk_all_finite)
#define erk_or_flight_advance NAMESPACED(erk_or_flight_advance)
#define erk_locate_root NAMESPACED(erk_locate_root)
#define erk_start NAMESPACED(erk_start)

/* cosim.c: Co-Simulation's integrator */
#define cosim_advance NAMESPACED(cosim_advance)
#define cosim_counts NAMESPACED(cosim_counts)
#define cosim_free NAMESPACED(cosim_free)
#define cosim_new NAMESPACED(cosim_new)
#define cosim_start NAMESPACED(cosim_start)
#endif

#endif
