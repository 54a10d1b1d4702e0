/* The texts of String ports: one number per distinct text, in the order first seen, the same
 * text always the same number (also after the table grew past many thousands), every number's
 * text returned as given, no text for a number never given; a String port connects to a
 * String port only, and unscaled. */
#include <math.h>
#include <stdio.h>

#include "test_support.h"

enum { MANY = 20000 };

static void numbers_in_order(void)
{
    ssx_system *sys = ssx_system_new("texts");
    CHECK(sys != NULL);
    CHECK(ssx_text_count(sys) == 0 && ssx_text(sys, 0.0) == NULL);
    char text[32];
    for (int k = 0; k < MANY; ++k) {
        snprintf(text, sizeof text, "text %d", k);
        double number = -1.0;
        CHECK_OK(sys, ssx_text_number(sys, text, &number));
        CHECK(number == (double)k);
    }
    CHECK(ssx_text_count(sys) == MANY);
    for (int k = MANY - 1; k >= 0; k -= 7) {
        snprintf(text, sizeof text, "text %d", k);
        double number = -1.0;
        CHECK_OK(sys, ssx_text_number(sys, text, &number));
        CHECK(number == (double)k);
        CHECK(strcmp(ssx_text(sys, (double)k), text) == 0);
    }
    double empty = -1.0;
    CHECK_OK(sys, ssx_text_number(sys, "", &empty));
    CHECK(empty == (double)MANY && strcmp(ssx_text(sys, empty), "") == 0);
    CHECK(ssx_text_count(sys) == MANY + 1);
    CHECK(ssx_text(sys, MANY + 1.0) == NULL && ssx_text(sys, -1.0) == NULL);
    CHECK(ssx_text(sys, 0.5) == NULL && ssx_text(sys, NAN) == NULL);
    ssx_system_free(sys);
}

static void strings_connect_to_strings(void)
{
    ssx_system *sys = ssx_system_new("ports");
    CHECK(sys != NULL);
    int a = ssx_add_python_component(sys, "A", 0);
    int b = ssx_add_python_component(sys, "B", 0);
    CHECK(a >= 0 && b >= 0);
    int text_out = ssx_add_output(sys, a, SSX_STRING, 0);
    int real_out = ssx_add_output(sys, a, SSX_REAL, 0);
    int text_in = ssx_add_input(sys, b, SSX_STRING, 0, 0.0);
    int real_in = ssx_add_input(sys, b, SSX_REAL, 0, 0.0);
    CHECK(text_out >= 0 && real_out >= 0 && text_in >= 0 && real_in >= 0);
    CHECK(ssx_connect(sys, a, text_out, b, real_in, 1.0, 0.0) != 0);
    CHECK_MESSAGE(sys, "connects to a port of its own type only");
    CHECK(ssx_connect(sys, a, real_out, b, text_in, 1.0, 0.0) != 0);
    CHECK(ssx_connect(sys, a, text_out, b, text_in, 2.0, 0.0) != 0);
    CHECK(ssx_connect(sys, a, text_out, b, text_in, 1.0, 1.0) != 0);
    CHECK_OK(sys, ssx_connect(sys, a, text_out, b, text_in, 1.0, 0.0));
    ssx_system_free(sys);
}

int main(void)
{
    numbers_in_order();
    strings_connect_to_strings();
    return 0;
}
