/* The C-variadic FMI 2.0 logger callback, which stable Rust cannot define: it
 * formats the message with vsnprintf and hands it to Rust. */
#include <stdarg.h>
#include <stdio.h>

void slender_fmi_log_sink(void *environment, const char *instance, int status,
                          const char *category, const char *message);

void slender_fmi_logger(void *environment, const char *instance, int status,
                        const char *category, const char *format, ...) {
    char message[4096];
    va_list arguments;
    va_start(arguments, format);
    vsnprintf(message, sizeof message, format ? format : "", arguments);
    va_end(arguments);
    slender_fmi_log_sink(environment, instance, status, category, message);
}
