/* Prints the size of each struct of robotd/robotd.h and the offset of each of its fields, as
 * JSON, so that the Python package's ctypes mirror of them (clients/python/robotd/_native.py) can
 * be checked against what the C compiler lays out. */
#include <robotd/robotd.h>
#include <stddef.h>
#include <stdio.h>

#define FIELD(type, field) printf("%s\"%s\": %zu", first ? "" : ", ", #field, offsetof(type, field)), first = 0

#define STRUCT(type, fields)                                                           \
  do {                                                                                 \
    int first = 1;                                                                     \
    printf("%s\"%s\": {\"size\": %zu, \"fields\": {", separator, #type, sizeof(type)); \
    fields;                                                                            \
    printf("}}");                                                                      \
    separator = ", ";                                                                  \
  } while (0)

int main(void) {
  const char* separator = "";
  printf("{");
  STRUCT(robotd_client_options,
         (FIELD(robotd_client_options, domain_id), FIELD(robotd_client_options, network_interface),
          FIELD(robotd_client_options, peers), FIELD(robotd_client_options, multicast),
          FIELD(robotd_client_options, node_name), FIELD(robotd_client_options, service_timeout_ms)));
  STRUCT(robotd_device_info, (FIELD(robotd_device_info, name), FIELD(robotd_device_info, driver),
                              FIELD(robotd_device_info, model), FIELD(robotd_device_info, kinematic_model),
                              FIELD(robotd_device_info, state), FIELD(robotd_device_info, rate_hz),
                              FIELD(robotd_device_info, joint_count), FIELD(robotd_device_info, joint_names),
                              FIELD(robotd_device_info, position_min), FIELD(robotd_device_info, position_max),
                              FIELD(robotd_device_info, velocity_max), FIELD(robotd_device_info, effort_max)));
  STRUCT(robotd_session_request,
         (FIELD(robotd_session_request, device), FIELD(robotd_session_request, motor_ids),
          FIELD(robotd_session_request, motor_count), FIELD(robotd_session_request, mode),
          FIELD(robotd_session_request, on_timeout), FIELD(robotd_session_request, timeout_ms),
          FIELD(robotd_session_request, default_kp), FIELD(robotd_session_request, default_kd),
          FIELD(robotd_session_request, on_release), FIELD(robotd_session_request, policy_name),
          FIELD(robotd_session_request, policy_file_name), FIELD(robotd_session_request, closed_loop),
          FIELD(robotd_session_request, min_command_success_rate), FIELD(robotd_session_request, on_low_success_rate)));
  STRUCT(robotd_command, (FIELD(robotd_command, motor_ids), FIELD(robotd_command, count),
                          FIELD(robotd_command, positions), FIELD(robotd_command, velocities),
                          FIELD(robotd_command, kp), FIELD(robotd_command, kd), FIELD(robotd_command, torques)));
  STRUCT(robotd_joint_state,
         (FIELD(robotd_joint_state, device), FIELD(robotd_joint_state, stamp_ns),
          FIELD(robotd_joint_state, joint_count), FIELD(robotd_joint_state, names), FIELD(robotd_joint_state, position),
          FIELD(robotd_joint_state, velocity), FIELD(robotd_joint_state, effort)));
  STRUCT(
      robotd_device_status,
      (FIELD(robotd_device_status, device), FIELD(robotd_device_status, stamp_ns), FIELD(robotd_device_status, state),
       FIELD(robotd_device_status, state_text), FIELD(robotd_device_status, fault_code),
       FIELD(robotd_device_status, fault_text), FIELD(robotd_device_status, estop_engaged),
       FIELD(robotd_device_status, loop_period_p50_us), FIELD(robotd_device_status, loop_period_p99_us),
       FIELD(robotd_device_status, loop_period_max_us), FIELD(robotd_device_status, loop_overruns),
       FIELD(robotd_device_status, commands_accepted), FIELD(robotd_device_status, commands_rejected)));
  STRUCT(robotd_tick_state,
         (FIELD(robotd_tick_state, device), FIELD(robotd_tick_state, tick), FIELD(robotd_tick_state, stamp_ns),
          FIELD(robotd_tick_state, deadline_steady_ns), FIELD(robotd_tick_state, period_ns),
          FIELD(robotd_tick_state, state_ready_steady_ns), FIELD(robotd_tick_state, published_steady_ns),
          FIELD(robotd_tick_state, state), FIELD(robotd_tick_state, joint_count), FIELD(robotd_tick_state, position),
          FIELD(robotd_tick_state, velocity), FIELD(robotd_tick_state, effort), FIELD(robotd_tick_state, has_imu),
          FIELD(robotd_tick_state, imu_orientation), FIELD(robotd_tick_state, imu_angular_velocity),
          FIELD(robotd_tick_state, imu_linear_acceleration)));
  STRUCT(robotd_session_info,
         (FIELD(robotd_session_info, session_id), FIELD(robotd_session_info, node_name),
          FIELD(robotd_session_info, device), FIELD(robotd_session_info, commands_accepted),
          FIELD(robotd_session_info, closed_loop), FIELD(robotd_session_info, ticks_to_answer),
          FIELD(robotd_session_info, ticks_answered_in_time), FIELD(robotd_session_info, ticks_answered_late),
          FIELD(robotd_session_info, ticks_unanswered), FIELD(robotd_session_info, command_success_rate),
          FIELD(robotd_session_info, min_command_success_rate), FIELD(robotd_session_info, on_low_success_rate),
          FIELD(robotd_session_info, success_rate_low)));
  STRUCT(robotd_move_options, (FIELD(robotd_move_options, duration_s), FIELD(robotd_move_options, speed_percent),
                               FIELD(robotd_move_options, acceleration_percent), FIELD(robotd_move_options, shape),
                               FIELD(robotd_move_options, stop)));
  STRUCT(robotd_move_report, (FIELD(robotd_move_report, stopped), FIELD(robotd_move_report, commands_sent),
                              FIELD(robotd_move_report, fraction_done), FIELD(robotd_move_report, joint_count),
                              FIELD(robotd_move_report, last_measured), FIELD(robotd_move_report, summary)));
  STRUCT(robotd_pose, (FIELD(robotd_pose, position_m), FIELD(robotd_pose, angles_rad)));
  STRUCT(robotd_rbtscript_options,
         (FIELD(robotd_rbtscript_options, device), FIELD(robotd_rbtscript_options, dry_run),
          FIELD(robotd_rbtscript_options, loops), FIELD(robotd_rbtscript_options, stop),
          FIELD(robotd_rbtscript_options, on_statement), FIELD(robotd_rbtscript_options, user_data),
          FIELD(robotd_rbtscript_options, session_timeout_ms)));
  STRUCT(robotd_rbtscript_problem,
         (FIELD(robotd_rbtscript_problem, line), FIELD(robotd_rbtscript_problem, column),
          FIELD(robotd_rbtscript_problem, statement), FIELD(robotd_rbtscript_problem, message),
          FIELD(robotd_rbtscript_problem, description)));
  STRUCT(robotd_rbtscript_outcome,
         (FIELD(robotd_rbtscript_outcome, device), FIELD(robotd_rbtscript_outcome, syntax_errors),
          FIELD(robotd_rbtscript_outcome, problem_count), FIELD(robotd_rbtscript_outcome, moves_planned),
          FIELD(robotd_rbtscript_outcome, pass_seconds), FIELD(robotd_rbtscript_outcome, end),
          FIELD(robotd_rbtscript_outcome, statements_run), FIELD(robotd_rbtscript_outcome, passes),
          FIELD(robotd_rbtscript_outcome, failure)));
  printf("}\n");
  return 0;
}
