// Closes the region bullet_warnings_off.h opened: our warnings apply again. No include guard.
#pragma GCC diagnostic pop
