/* lt_status.h - status codes returned by every fallible core function.
 * LT_OK is 0 and errors are negative; outputs always go through pointer parameters.
 * Builds: all.
 */
#ifndef LT_STATUS_H
#define LT_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum lt_status {
    LT_OK = 0,
    LT_E_ARG = -1,    /* a NULL pointer, a zero count or an argument outside its documented domain */
    LT_E_RANGE = -2,  /* a value does not fit its fixed-point format (e.g. a scene too large) */
    LT_E_SPACE = -3,  /* the caller's buffer is too small; the needed size was written back */
    LT_E_FORMAT = -4, /* malformed input data */
    LT_E_DEPTH = -5   /* a stack, tree or step limit was reached */
} lt_status_t;

/* Short English text for a status ("ok", "invalid argument", ...); "" when LT_CFG_NO_STATUS_STRINGS.
 * Returns: a static string, never NULL. */
const char *lt_status_str(lt_status_t s);

#ifdef __cplusplus
}
#endif
#endif /* LT_STATUS_H */
