/* placeholder replaced by the port layer */
typedef int pft_port_placeholder_t;
