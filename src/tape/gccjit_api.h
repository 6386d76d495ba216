/* libgccjit through a table of function pointers filled on first use
 * (gccjit_api.c), so that a command that never compiles never loads it:
 * libgccjit and the libraries behind it cost some 12 ms at start-up.
 *
 * The gcc_jit_* names used by jit_common.c, jit_eval.c, jit_newton.c and
 * jit_taylor.c become calls through the table by the macros below, so those
 * files only include this header instead of <libgccjit.h>.  Types and
 * enums (GCC_JIT_OUTPUT_KIND_* ...) still come from <libgccjit.h>, which is
 * needed at build time (libgccjit-12-dev) but not linked.
 *
 * A name missing from HL_GCCJIT_FUNCTIONS fails at link time with an
 * undefined gcc_jit_* reference: add one X(...) line and one #define. */
#ifndef HAMLIE_TAPE_GCCJIT_API_H
#define HAMLIE_TAPE_GCCJIT_API_H

#ifdef HAMLIE_HAVE_GCCJIT
#include <libgccjit.h>

#include "hamlie/error.h"

#define HL_GCCJIT_FUNCTIONS(X)                                                                     \
    X(gcc_jit_context_acquire)                                                                     \
    X(gcc_jit_context_release)                                                                     \
    X(gcc_jit_context_set_int_option)                                                              \
    X(gcc_jit_context_set_bool_option)                                                             \
    X(gcc_jit_context_set_bool_print_errors_to_stderr)                                             \
    X(gcc_jit_context_set_str_option)                                                              \
    X(gcc_jit_context_add_command_line_option)                                                     \
    X(gcc_jit_context_add_driver_option)                                                           \
    X(gcc_jit_context_compile)                                                                     \
    X(gcc_jit_context_compile_to_file)                                                             \
    X(gcc_jit_context_get_first_error)                                                             \
    X(gcc_jit_context_get_last_error)                                                              \
    X(gcc_jit_context_dump_to_file)                                                                \
    X(gcc_jit_context_dump_reproducer_to_file)                                                     \
    X(gcc_jit_result_get_code)                                                                     \
    X(gcc_jit_result_get_global)                                                                   \
    X(gcc_jit_result_release)                                                                      \
    X(gcc_jit_version_major)                                                                       \
    X(gcc_jit_version_minor)                                                                       \
    X(gcc_jit_version_patchlevel)                                                                  \
    X(gcc_jit_context_get_type)                                                                    \
    X(gcc_jit_context_get_int_type)                                                                \
    X(gcc_jit_type_get_pointer)                                                                    \
    X(gcc_jit_type_get_const)                                                                      \
    X(gcc_jit_context_new_array_type)                                                              \
    X(gcc_jit_context_new_param)                                                                   \
    X(gcc_jit_param_as_rvalue)                                                                     \
    X(gcc_jit_param_as_lvalue)                                                                     \
    X(gcc_jit_context_new_function)                                                                \
    X(gcc_jit_context_get_builtin_function)                                                        \
    X(gcc_jit_function_new_local)                                                                  \
    X(gcc_jit_function_new_block)                                                                  \
    X(gcc_jit_context_new_rvalue_from_double)                                                      \
    X(gcc_jit_context_new_rvalue_from_int)                                                         \
    X(gcc_jit_context_new_rvalue_from_long)                                                        \
    X(gcc_jit_context_zero)                                                                        \
    X(gcc_jit_context_one)                                                                         \
    X(gcc_jit_context_new_unary_op)                                                                \
    X(gcc_jit_context_new_binary_op)                                                               \
    X(gcc_jit_context_new_comparison)                                                              \
    X(gcc_jit_context_new_call)                                                                    \
    X(gcc_jit_context_new_cast)                                                                    \
    X(gcc_jit_context_new_array_access)                                                            \
    X(gcc_jit_lvalue_as_rvalue)                                                                    \
    X(gcc_jit_lvalue_get_address)                                                                  \
    X(gcc_jit_rvalue_dereference)                                                                  \
    X(gcc_jit_block_add_assignment)                                                                \
    X(gcc_jit_block_add_assignment_op)                                                             \
    X(gcc_jit_block_add_eval)                                                                      \
    X(gcc_jit_block_end_with_jump)                                                                 \
    X(gcc_jit_block_end_with_conditional)                                                          \
    X(gcc_jit_block_end_with_return)                                                               \
    X(gcc_jit_block_end_with_void_return)                                                          \
    X(gcc_jit_type_get_vector)                                                                     \
    X(gcc_jit_context_new_rvalue_from_vector)

/* One pointer per function, of the type <libgccjit.h> declares it with. */
typedef struct hl_gccjit_api {
#define HL_GCCJIT_SLOT(name) __typeof__(name) *name;
    HL_GCCJIT_FUNCTIONS(HL_GCCJIT_SLOT)
#undef HL_GCCJIT_SLOT
} hl_gccjit_api;

extern hl_gccjit_api hl_gccjit;

/* Load the library once per process: $HAMLIE_GCCJIT_LIB if set (tests set
 * a missing one), else libgccjit.so.0.  HL_OK when every function of the
 * table was found; else HL_EUNSUP, "libgccjit.so.0 not found: install ...;
 * running interpreted", the same on every later call. */
hl_status hl_gccjit_load(hl_error *err);

/* 1 unless loading was tried and failed (it is not tried here). */
int hl_gccjit_not_failed(void);

/* The calls go through the table (not in gccjit_api.c, which fills it). */
#ifndef HL_GCCJIT_API_IMPL
#define gcc_jit_context_acquire (hl_gccjit.gcc_jit_context_acquire)
#define gcc_jit_context_release (hl_gccjit.gcc_jit_context_release)
#define gcc_jit_context_set_int_option (hl_gccjit.gcc_jit_context_set_int_option)
#define gcc_jit_context_set_bool_option (hl_gccjit.gcc_jit_context_set_bool_option)
#define gcc_jit_context_set_bool_print_errors_to_stderr                                            \
    (hl_gccjit.gcc_jit_context_set_bool_print_errors_to_stderr)
#define gcc_jit_context_set_str_option (hl_gccjit.gcc_jit_context_set_str_option)
#define gcc_jit_context_add_command_line_option (hl_gccjit.gcc_jit_context_add_command_line_option)
#define gcc_jit_context_add_driver_option (hl_gccjit.gcc_jit_context_add_driver_option)
#define gcc_jit_context_compile (hl_gccjit.gcc_jit_context_compile)
#define gcc_jit_context_compile_to_file (hl_gccjit.gcc_jit_context_compile_to_file)
#define gcc_jit_context_get_first_error (hl_gccjit.gcc_jit_context_get_first_error)
#define gcc_jit_context_get_last_error (hl_gccjit.gcc_jit_context_get_last_error)
#define gcc_jit_context_dump_to_file (hl_gccjit.gcc_jit_context_dump_to_file)
#define gcc_jit_context_dump_reproducer_to_file (hl_gccjit.gcc_jit_context_dump_reproducer_to_file)
#define gcc_jit_result_get_code (hl_gccjit.gcc_jit_result_get_code)
#define gcc_jit_result_get_global (hl_gccjit.gcc_jit_result_get_global)
#define gcc_jit_result_release (hl_gccjit.gcc_jit_result_release)
#define gcc_jit_version_major (hl_gccjit.gcc_jit_version_major)
#define gcc_jit_version_minor (hl_gccjit.gcc_jit_version_minor)
#define gcc_jit_version_patchlevel (hl_gccjit.gcc_jit_version_patchlevel)
#define gcc_jit_context_get_type (hl_gccjit.gcc_jit_context_get_type)
#define gcc_jit_context_get_int_type (hl_gccjit.gcc_jit_context_get_int_type)
#define gcc_jit_type_get_pointer (hl_gccjit.gcc_jit_type_get_pointer)
#define gcc_jit_type_get_const (hl_gccjit.gcc_jit_type_get_const)
#define gcc_jit_context_new_array_type (hl_gccjit.gcc_jit_context_new_array_type)
#define gcc_jit_context_new_param (hl_gccjit.gcc_jit_context_new_param)
#define gcc_jit_param_as_rvalue (hl_gccjit.gcc_jit_param_as_rvalue)
#define gcc_jit_param_as_lvalue (hl_gccjit.gcc_jit_param_as_lvalue)
#define gcc_jit_context_new_function (hl_gccjit.gcc_jit_context_new_function)
#define gcc_jit_context_get_builtin_function (hl_gccjit.gcc_jit_context_get_builtin_function)
#define gcc_jit_function_new_local (hl_gccjit.gcc_jit_function_new_local)
#define gcc_jit_function_new_block (hl_gccjit.gcc_jit_function_new_block)
#define gcc_jit_context_new_rvalue_from_double (hl_gccjit.gcc_jit_context_new_rvalue_from_double)
#define gcc_jit_context_new_rvalue_from_int (hl_gccjit.gcc_jit_context_new_rvalue_from_int)
#define gcc_jit_context_new_rvalue_from_long (hl_gccjit.gcc_jit_context_new_rvalue_from_long)
#define gcc_jit_context_zero (hl_gccjit.gcc_jit_context_zero)
#define gcc_jit_context_one (hl_gccjit.gcc_jit_context_one)
#define gcc_jit_context_new_unary_op (hl_gccjit.gcc_jit_context_new_unary_op)
#define gcc_jit_context_new_binary_op (hl_gccjit.gcc_jit_context_new_binary_op)
#define gcc_jit_context_new_comparison (hl_gccjit.gcc_jit_context_new_comparison)
#define gcc_jit_context_new_call (hl_gccjit.gcc_jit_context_new_call)
#define gcc_jit_context_new_cast (hl_gccjit.gcc_jit_context_new_cast)
#define gcc_jit_context_new_array_access (hl_gccjit.gcc_jit_context_new_array_access)
#define gcc_jit_lvalue_as_rvalue (hl_gccjit.gcc_jit_lvalue_as_rvalue)
#define gcc_jit_lvalue_get_address (hl_gccjit.gcc_jit_lvalue_get_address)
#define gcc_jit_rvalue_dereference (hl_gccjit.gcc_jit_rvalue_dereference)
#define gcc_jit_block_add_assignment (hl_gccjit.gcc_jit_block_add_assignment)
#define gcc_jit_block_add_assignment_op (hl_gccjit.gcc_jit_block_add_assignment_op)
#define gcc_jit_block_add_eval (hl_gccjit.gcc_jit_block_add_eval)
#define gcc_jit_block_end_with_jump (hl_gccjit.gcc_jit_block_end_with_jump)
#define gcc_jit_block_end_with_conditional (hl_gccjit.gcc_jit_block_end_with_conditional)
#define gcc_jit_block_end_with_return (hl_gccjit.gcc_jit_block_end_with_return)
#define gcc_jit_block_end_with_void_return (hl_gccjit.gcc_jit_block_end_with_void_return)
#define gcc_jit_type_get_vector (hl_gccjit.gcc_jit_type_get_vector)
#define gcc_jit_context_new_rvalue_from_vector (hl_gccjit.gcc_jit_context_new_rvalue_from_vector)
#endif /* HL_GCCJIT_API_IMPL */

#endif /* HAMLIE_HAVE_GCCJIT */
#endif
