/* The public header compiles as strict C99 on its own (-std=c99 -Wall -Wextra -Werror -pedantic).
 */
#include "progsim.h"

int main(void) {
  return ps_version() == PS_VERSION_HEADER ? 0 : 1;
}
