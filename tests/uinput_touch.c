/* uinput_touch HOLD_MS: a virtual touch screen through /dev/uinput (Linux),
 * as a kiosk's panel would be: it appears, waits for SIGUSR1 (the program
 * under test has found it and draws), at most HOLD_MS, swipes a finger from
 * the left third to the right third of the screen over half a second,
 * lifts it, waits HOLD_MS again and goes. It waited a fixed time before:
 * under TCG on a slow host the kiosk took longer than that to start, and
 * the swipe went by unseen. For tools/kms-test.sh's guest; needs root (or
 * /dev/uinput access). */
#define _POSIX_C_SOURCE 200112L
#include <fcntl.h>
#include <signal.h>
#include <linux/uinput.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

static int fd;

static void emit(int type, int code, int value)
{
    struct input_event e;
    memset(&e, 0, sizeof e);
    e.type = (unsigned short)type;
    e.code = (unsigned short)code;
    e.value = value;
    if (write(fd, &e, sizeof e) != (ssize_t)sizeof e) perror("uinput_touch: write");
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static void axis(int code, int max)
{
    struct uinput_abs_setup a;
    memset(&a, 0, sizeof a);
    a.code = (unsigned short)code;
    a.absinfo.maximum = max;
    a.absinfo.resolution = 10;
    ioctl(fd, UI_ABS_SETUP, &a);
}

int main(int argc, char **argv)
{
    int hold = argc > 1 ? atoi(argv[1]) : 3000;
    /* Blocked before the device appears, so that a signal sent as soon as
     * it is found waits for sigtimedwait instead of ending the program. */
    sigset_t go;
    sigemptyset(&go);
    sigaddset(&go, SIGUSR1);
    sigprocmask(SIG_BLOCK, &go, NULL);
    fd = open("/dev/uinput", O_WRONLY | O_NONBLOCK);
    if (fd < 0) { perror("uinput_touch: /dev/uinput"); return 1; }
    ioctl(fd, UI_SET_EVBIT, EV_KEY);
    ioctl(fd, UI_SET_KEYBIT, BTN_TOUCH);
    ioctl(fd, UI_SET_EVBIT, EV_ABS);
    ioctl(fd, UI_SET_ABSBIT, ABS_X);
    ioctl(fd, UI_SET_ABSBIT, ABS_Y);
    ioctl(fd, UI_SET_ABSBIT, ABS_MT_SLOT);
    ioctl(fd, UI_SET_ABSBIT, ABS_MT_TRACKING_ID);
    ioctl(fd, UI_SET_ABSBIT, ABS_MT_POSITION_X);
    ioctl(fd, UI_SET_ABSBIT, ABS_MT_POSITION_Y);
    ioctl(fd, UI_SET_PROPBIT, INPUT_PROP_DIRECT); /* a touch screen, not a touchpad */
    axis(ABS_X, 1023);
    axis(ABS_Y, 767);
    axis(ABS_MT_POSITION_X, 1023);
    axis(ABS_MT_POSITION_Y, 767);
    axis(ABS_MT_TRACKING_ID, 65535);
    axis(ABS_MT_SLOT, 1);
    struct uinput_setup us;
    memset(&us, 0, sizeof us);
    us.id.bustype = BUS_VIRTUAL;
    us.id.vendor = 0x1234;
    us.id.product = 0x5678;
    snprintf(us.name, sizeof us.name, "jade test touch screen");
    if (ioctl(fd, UI_DEV_SETUP, &us) < 0 || ioctl(fd, UI_DEV_CREATE) < 0) {
        perror("uinput_touch: create");
        return 1;
    }
    printf("uinput_touch: touch screen created, waiting for SIGUSR1 (at most %d ms)\n", hold);
    fflush(stdout);
    struct timespec ts = {hold / 1000, (long)(hold % 1000) * 1000000L};
    if (sigtimedwait(&go, NULL, &ts) < 0) printf("uinput_touch: no SIGUSR1 in %d ms: swiping anyway\n", hold);
    for (int i = 0; i <= 20; i++) {
        int x = 340 + i * 17, y = 384;
        if (i == 0) {
            emit(EV_ABS, ABS_MT_SLOT, 0);
            emit(EV_ABS, ABS_MT_TRACKING_ID, 1);
            emit(EV_KEY, BTN_TOUCH, 1);
        }
        emit(EV_ABS, ABS_MT_POSITION_X, x);
        emit(EV_ABS, ABS_MT_POSITION_Y, y);
        emit(EV_ABS, ABS_X, x);
        emit(EV_ABS, ABS_Y, y);
        emit(EV_SYN, SYN_REPORT, 0);
        sleep_ms(25);
    }
    emit(EV_ABS, ABS_MT_TRACKING_ID, -1);
    emit(EV_KEY, BTN_TOUCH, 0);
    emit(EV_SYN, SYN_REPORT, 0);
    printf("uinput_touch: swiped 340 px to the right\n");
    fflush(stdout);
    sleep_ms(hold);
    ioctl(fd, UI_DEV_DESTROY);
    close(fd);
    return 0;
}
