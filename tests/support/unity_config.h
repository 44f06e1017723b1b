/* pftrack's Unity configuration (used on host, under qemu-user and on bare metal). */
#ifndef PFT_UNITY_CONFIG_H
#define PFT_UNITY_CONFIG_H
#define UNITY_INCLUDE_DOUBLE
#define UNITY_SUPPORT_64
#define UNITY_INCLUDE_PRINT_FORMATTED
#endif
